#include "tightfit/geometry/plane_loops.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <map>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

using Edge = std::pair<int, int>;  // (smaller, larger) vertex index

Edge edge_key(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

bool negative(const std::vector<double>& side, int v) { return side[static_cast<size_t>(v)] < 0.0; }

/// The crossed edges, grouped into loops: two crossed edges are in one loop when a
/// face holds both.
class CutLoops {
 public:
  CutLoops(const TriMesh& mesh, const std::vector<double>& side) {
    for (int f = 0; f < mesh.num_faces(); ++f) {
      std::array<int, 3> crossing{};
      int count = 0;
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
        if (negative(side, a) != negative(side, b)) crossing[static_cast<size_t>(count++)] = index_of(edge_key(a, b));
      }
      if (count == 2) unite(crossing[0], crossing[1]);
    }
  }

  const std::vector<Edge>& edges() const { return edges_; }
  /// Loop label of crossed edge i.
  int loop_of(int i) {
    while (parent_[static_cast<size_t>(i)] != i)
      i = parent_[static_cast<size_t>(i)] = parent_[static_cast<size_t>(parent_[static_cast<size_t>(i)])];
    return i;
  }

 private:
  int index_of(const Edge& e) {
    const auto [it, added] = index_.emplace(e, static_cast<int>(edges_.size()));
    if (added) {
      edges_.push_back(e);
      parent_.push_back(it->second);
    }
    return it->second;
  }
  void unite(int a, int b) { parent_[static_cast<size_t>(loop_of(a))] = loop_of(b); }

  std::map<Edge, int> index_;
  std::vector<Edge> edges_;
  std::vector<int> parent_;
};

}  // namespace

BeyondLoop beyond_nearest_loop(const TriMesh& mesh, const std::vector<double>& side, const Vec3& point,
                               const Vec3& normal, const std::string& source) {
  const int nv = mesh.num_vertices();
  CutLoops loops(mesh, side);
  if (loops.edges().empty()) throw InputError(source, "the plane misses the surface");
  // The crossing points, in plane coordinates around `point`.
  const Vec3 n = normal.normalized(), u = n.unitOrthogonal(), v_axis = n.cross(u);
  const size_t ne = loops.edges().size();
  std::vector<Eigen::Vector2d> crossing(ne);
  std::vector<double> distance(ne);
  std::map<Edge, int> index;
  for (size_t i = 0; i < ne; ++i) {
    const auto [a, b] = loops.edges()[i];
    const double da = side[static_cast<size_t>(a)], db = side[static_cast<size_t>(b)];
    const double t = da / (da - db);
    const Vec3 x = (1.0 - t) * mesh.vertices.row(a).transpose() + t * mesh.vertices.row(b).transpose() - point;
    crossing[i] = Eigen::Vector2d(u.dot(x), v_axis.dot(x));
    distance[i] = x.norm();
    index.emplace(loops.edges()[i], static_cast<int>(i));
  }
  // Which loops go around the point: a ray from it along u crosses an odd number of
  // their segments (one segment per face the loop crosses).
  std::map<int, int> ray_crossings;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    std::array<int, 3> ends{};
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (negative(side, a) != negative(side, b)) ends[static_cast<size_t>(count++)] = index.at(edge_key(a, b));
    }
    if (count != 2) continue;
    const Eigen::Vector2d p = crossing[static_cast<size_t>(ends[0])], q = crossing[static_cast<size_t>(ends[1])];
    if ((p.y() > 0.0) != (q.y() > 0.0) && p.x() + (q.x() - p.x()) * (0.0 - p.y()) / (q.y() - p.y()) > 0.0)
      ++ray_crossings[loops.loop_of(ends[0])];
  }
  // The nearest loop around the point, else the nearest loop.
  int nearest_loop = -1;
  bool nearest_encloses = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < ne; ++i) {
    const int loop = loops.loop_of(static_cast<int>(i));
    const bool encloses = ray_crossings[loop] % 2 == 1;
    if ((encloses && !nearest_encloses) || (encloses == nearest_encloses && distance[i] < nearest)) {
      nearest = distance[i];
      nearest_loop = loop;
      nearest_encloses = encloses;
    }
  }
  BeyondLoop out;
  for (int i = 0; i < static_cast<int>(loops.edges().size()); ++i)
    if (loops.loop_of(i) == nearest_loop) out.loop_edges.push_back(loops.edges()[static_cast<size_t>(i)]);
  std::sort(out.loop_edges.begin(), out.loop_edges.end());
  auto on_loop = [&](int a, int b) {
    return std::binary_search(out.loop_edges.begin(), out.loop_edges.end(), edge_key(a, b));
  };

  std::vector<std::vector<int>> neighbours(static_cast<size_t>(nv));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      neighbours[static_cast<size_t>(mesh.faces(f, k))].push_back(mesh.faces(f, (k + 1) % 3));
  out.beyond.assign(static_cast<size_t>(nv), 0);
  std::vector<int> stack;
  for (const auto& [a, b] : out.loop_edges) {
    const int v = negative(side, a) ? a : b;
    if (!out.beyond[static_cast<size_t>(v)]) {
      out.beyond[static_cast<size_t>(v)] = 1;
      stack.push_back(v);
    }
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : neighbours[static_cast<size_t>(v)]) {
      if (out.beyond[static_cast<size_t>(w)] || on_loop(v, w)) continue;
      out.beyond[static_cast<size_t>(w)] = 1;
      stack.push_back(w);
    }
  }
  for (const auto& [a, b] : out.loop_edges)
    if (out.beyond[static_cast<size_t>(negative(side, a) ? b : a)])
      throw InputError(source, "the cut loop nearest the point does not separate the surface "
                               "(the surface has a handle through it)");
  return out;
}

}  // namespace tightfit
