#include "tightfit/geometry/surface_topology.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tightfit {

namespace {

struct HalfEdgeKey {
  int lo, hi, code;  // code = 3*face + i
};

/// Union-find over a dense index range, with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(static_cast<size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace

SurfaceTopology::SurfaceTopology(const Triangles& faces, int num_vertices)
    : num_vertices_(num_vertices), faces_(faces) {
  if (num_vertices < 0) throw std::invalid_argument("SurfaceTopology: negative vertex count");
  const int m = static_cast<int>(faces.rows());
  std::vector<HalfEdgeKey> keys;
  keys.reserve(static_cast<size_t>(3 * m));
  for (int f = 0; f < m; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int a = faces(f, i);
      const int b = faces(f, (i + 1) % 3);
      if (a < 0 || a >= num_vertices || b < 0 || b >= num_vertices)
        throw std::invalid_argument("SurfaceTopology: face " + std::to_string(f) +
                                    " has a vertex index outside [0, " +
                                    std::to_string(num_vertices) + ")");
      keys.push_back({std::min(a, b), std::max(a, b), 3 * f + i});
    }
  }
  std::sort(keys.begin(), keys.end(), [](const HalfEdgeKey& x, const HalfEdgeKey& y) {
    if (x.lo != y.lo) return x.lo < y.lo;
    if (x.hi != y.hi) return x.hi < y.hi;
    return x.code < y.code;
  });

  face_edges_.assign(static_cast<size_t>(m), {-1, -1, -1});
  edge_half_.reserve(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    if (k == 0 || keys[k].lo != keys[k - 1].lo || keys[k].hi != keys[k - 1].hi) {
      edge_start_.push_back(static_cast<int>(edge_half_.size()));
      edge_vertices_.push_back({keys[k].lo, keys[k].hi});
    }
    const int e = static_cast<int>(edge_vertices_.size()) - 1;
    face_edges_[keys[k].code / 3][keys[k].code % 3] = e;
    edge_half_.push_back(keys[k].code);
  }
  edge_start_.push_back(static_cast<int>(edge_half_.size()));

  vertex_faces_.assign(static_cast<size_t>(num_vertices), {});
  for (int f = 0; f < m; ++f) {
    for (int i = 0; i < 3; ++i) {
      auto& list = vertex_faces_[faces(f, i)];
      if (list.empty() || list.back() != f) list.push_back(f);
    }
  }
  vertex_edges_.assign(static_cast<size_t>(num_vertices), {});
  for (int e = 0; e < num_edges(); ++e) {
    const auto [lo, hi] = edge_vertices_[e];
    vertex_edges_[lo].push_back(e);
    if (hi != lo) vertex_edges_[hi].push_back(e);
  }
  // Edges were created in (lo, hi) order, so each vertex's hi-side edges come in
  // ascending order too, but the two sides interleave: sort.
  for (auto& list : vertex_edges_) std::sort(list.begin(), list.end());
}

std::array<int, 2> SurfaceTopology::edge_faces(int edge) const {
  const int begin = edge_start_[edge];
  const int count = edge_valence(edge);
  return {edge_half_[begin] / 3, count > 1 ? edge_half_[begin + 1] / 3 : -1};
}

std::vector<int> SurfaceTopology::edge_all_faces(int edge) const {
  std::vector<int> out;
  for (int k = edge_start_[edge]; k < edge_start_[edge + 1]; ++k) out.push_back(edge_half_[k] / 3);
  return out;
}

SurfaceTopology::Across SurfaceTopology::across(int face, int i) const {
  const int e = face_edges_[face][i];
  if (edge_valence(e) != 2) return {-1, -1};
  const int self = 3 * face + i;
  const int a = edge_half_[edge_start_[e]];
  const int b = edge_half_[edge_start_[e] + 1];
  const int other = (a == self) ? b : a;
  return {other / 3, other % 3};
}

std::vector<int> SurfaceTopology::vertex_neighbors(int v) const {
  std::vector<int> out;
  out.reserve(vertex_edges_[v].size());
  for (int e : vertex_edges_[v]) {
    const auto [lo, hi] = edge_vertices_[e];
    const int w = (lo == v) ? hi : lo;
    if (w != v) out.push_back(w);
  }
  std::sort(out.begin(), out.end());
  return out;
}

int SurfaceTopology::find_edge(int a, int b) const {
  if (a < 0 || a >= num_vertices_ || b < 0 || b >= num_vertices_) return -1;
  const int lo = std::min(a, b);
  const int hi = std::max(a, b);
  for (int e : vertex_edges_[lo])
    if (edge_vertices_[e][0] == lo && edge_vertices_[e][1] == hi) return e;
  return -1;
}

bool SurfaceTopology::is_closed() const {
  for (int e = 0; e < num_edges(); ++e)
    if (is_boundary_edge(e)) return false;
  return true;
}

std::vector<int> SurfaceTopology::boundary_edges() const {
  std::vector<int> out;
  for (int e = 0; e < num_edges(); ++e)
    if (is_boundary_edge(e)) out.push_back(e);
  return out;
}

std::vector<std::vector<int>> SurfaceTopology::boundary_loops() const {
  // Directed boundary edges (from -> to, in face orientation), grouped by start vertex.
  const std::vector<int> boundary = boundary_edges();
  auto directed = [&](int e) {
    const int code = edge_half_[edge_start_[e]];
    return std::array<int, 2>{faces_(code / 3, code % 3), faces_(code / 3, (code % 3 + 1) % 3)};
  };
  std::vector<std::vector<int>> outgoing(static_cast<size_t>(num_vertices_));
  std::vector<std::array<int, 2>> dir(static_cast<size_t>(num_edges()), {-1, -1});
  for (int e : boundary) {
    dir[e] = directed(e);
    outgoing[dir[e][0]].push_back(e);
  }
  // The boundary edge that follows boundary edge e: rotate around its end vertex v
  // through the fan of e's face until the next boundary edge leaving v. This keeps
  // loops apart at pinch (bow-tie) vertices. If the fan walk fails (non-manifold
  // edge, inconsistent orientation), fall back to any unused boundary edge leaving v.
  std::vector<char> used(static_cast<size_t>(num_edges()), 0);
  auto follow = [&](int e) {
    const int v = dir[e][1];
    const int code = edge_half_[edge_start_[e]];
    int f = code / 3;
    int j = (code % 3 + 1) % 3;  // face edge of f leaving v
    const int limit = static_cast<int>(vertex_faces_[v].size()) + 1;
    for (int step = 0; step < limit && faces_(f, j) == v; ++step) {
      const int edge = face_edges_[f][j];
      if (is_boundary_edge(edge)) return used[edge] ? -1 : edge;
      const Across nb = across(f, j);
      if (nb.face < 0) break;
      f = nb.face;
      j = (nb.edge_in_face + 1) % 3;
    }
    for (int cand : outgoing[v])
      if (!used[cand]) return cand;
    return -1;
  };
  std::vector<std::vector<int>> loops;
  for (int start : boundary) {
    if (used[start]) continue;
    std::vector<int> loop;
    for (int e = start; e >= 0 && !used[e]; e = follow(e)) {
      used[e] = 1;
      loop.push_back(dir[e][0]);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<int> SurfaceTopology::non_manifold_edges() const {
  std::vector<int> out;
  for (int e = 0; e < num_edges(); ++e)
    if (edge_valence(e) > 2) out.push_back(e);
  return out;
}

std::vector<int> SurfaceTopology::non_manifold_vertices() const {
  // Connected components of the incident faces of each vertex, linked through edges
  // incident to the vertex. Work per vertex with local indices (valences are small).
  std::vector<int> out;
  for (int v = 0; v < num_vertices_; ++v) {
    const auto& fv = vertex_faces_[v];
    if (fv.size() <= 1) continue;
    DisjointSets sets(static_cast<int>(fv.size()));
    auto local = [&](int f) {
      return static_cast<int>(std::lower_bound(fv.begin(), fv.end(), f) - fv.begin());
    };
    for (int e : vertex_edges_[v]) {
      const int first = local(edge_half_[edge_start_[e]] / 3);
      for (int k = edge_start_[e] + 1; k < edge_start_[e + 1]; ++k)
        sets.unite(first, local(edge_half_[k] / 3));
    }
    for (int k = 1; k < static_cast<int>(fv.size()); ++k)
      if (sets.find(k) != 0) {
        out.push_back(v);
        break;
      }
  }
  return out;
}

std::vector<int> SurfaceTopology::inconsistently_oriented_edges() const {
  // Face edge i of face f runs corner i -> corner i+1; two face edges on the same
  // undirected edge agree when their start vertices differ. Self-loop edges of
  // degenerate faces have no direction and are skipped.
  auto from_vertex = [&](int code) { return faces_(code / 3, code % 3); };
  std::vector<int> out;
  for (int e = 0; e < num_edges(); ++e) {
    if (edge_valence(e) != 2) continue;
    if (edge_vertices_[e][0] == edge_vertices_[e][1]) continue;
    if (from_vertex(edge_half_[edge_start_[e]]) == from_vertex(edge_half_[edge_start_[e] + 1]))
      out.push_back(e);
  }
  return out;
}

std::vector<int> SurfaceTopology::isolated_vertices() const {
  std::vector<int> out;
  for (int v = 0; v < num_vertices_; ++v)
    if (vertex_faces_[v].empty()) out.push_back(v);
  return out;
}

}  // namespace tightfit
