#include "tightfit/geometry/plane_loops.hpp"

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

BeyondLoop beyond_nearest_loop(const TriMesh& mesh, const std::vector<double>& side,
                               const Vec3& point, const std::string& source) {
  const int nv = mesh.num_vertices();
  CutLoops loops(mesh, side);
  if (loops.edges().empty()) throw InputError(source, "the plane misses the surface");
  int nearest_loop = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(loops.edges().size()); ++i) {
    const auto [a, b] = loops.edges()[static_cast<size_t>(i)];
    const double da = side[static_cast<size_t>(a)], db = side[static_cast<size_t>(b)];
    const double t = da / (da - db);
    const Vec3 crossing = (1.0 - t) * mesh.vertices.row(a).transpose() + t * mesh.vertices.row(b).transpose();
    const double d = (crossing - point).norm();
    if (d < nearest) {
      nearest = d;
      nearest_loop = loops.loop_of(i);
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
