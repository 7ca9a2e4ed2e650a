#include "tightfit/garment/boundary_chords.hpp"

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace tightfit {
namespace {

using Edge = std::pair<int, int>;

/// The first chord (ascending) of `tris`: an edge with two triangles and both ends below
/// `num_boundary`; {-1, -1} when there is none.
Edge first_chord(const std::vector<std::array<int, 3>>& tris, int num_boundary) {
  std::map<Edge, int> count;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      if (a < num_boundary && b < num_boundary) ++count[Edge(std::minmax(a, b))];
    }
  for (const auto& [edge, n] : count)
    if (n == 2) return edge;
  return {-1, -1};
}

}  // namespace

int split_boundary_chords(PieceMesh& mesh, int num_boundary) {
  std::vector<std::array<int, 3>> tris(static_cast<size_t>(mesh.triangles.rows()));
  for (size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c)
      tris[t][static_cast<size_t>(c)] = mesh.triangles(static_cast<Eigen::Index>(t), c);
  std::vector<Vec2> points(static_cast<size_t>(mesh.vertices.rows()));
  for (size_t v = 0; v < points.size(); ++v)
    points[v] = mesh.vertices.row(static_cast<Eigen::Index>(v)).transpose();

  int splits = 0;
  for (Edge chord = first_chord(tris, num_boundary); chord.first >= 0;
       chord = first_chord(tris, num_boundary)) {
    const int m = static_cast<int>(points.size());
    points.push_back(0.5 * (points[static_cast<size_t>(chord.first)] +
                            points[static_cast<size_t>(chord.second)]));
    const size_t num_tris = tris.size();
    for (size_t t = 0; t < num_tris; ++t)
      for (int k = 0; k < 3; ++k) {
        const int p = tris[t][static_cast<size_t>(k)];
        const int q = tris[t][static_cast<size_t>((k + 1) % 3)];
        const int r = tris[t][static_cast<size_t>((k + 2) % 3)];
        if (Edge(std::minmax(p, q)) != chord) continue;
        tris[t] = {p, m, r};  // (p, q, r) becomes (p, m, r) and (m, q, r)
        tris.push_back({m, q, r});
        break;
      }
    ++splits;
  }

  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (size_t v = 0; v < points.size(); ++v)
    mesh.vertices.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  mesh.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c)
      mesh.triangles(static_cast<Eigen::Index>(t), c) = tris[t][static_cast<size_t>(c)];
  return splits;
}

}  // namespace tightfit
