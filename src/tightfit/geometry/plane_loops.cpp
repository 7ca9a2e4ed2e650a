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

/// Union-find over the crossed edges.
struct Labels {
  std::vector<int> parent;
  int find(int i) {
    while (parent[static_cast<size_t>(i)] != i)
      i = parent[static_cast<size_t>(i)] =
          parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    return i;
  }
};

}  // namespace

PlaneCut cut_by_plane(const TriMesh& mesh, const std::vector<double>& side) {
  PlaneCut cut;
  std::map<Edge, int> index;
  Labels labels;
  auto index_of = [&](const Edge& e) {
    const auto [it, added] = index.emplace(e, static_cast<int>(cut.edges.size()));
    if (added) {
      cut.edges.push_back(e);
      labels.parent.push_back(it->second);
      const double da = side[static_cast<size_t>(e.first)],
                   db = side[static_cast<size_t>(e.second)];
      cut.t.push_back(da / (da - db));
    }
    return it->second;
  };
  std::vector<int> faces_per_edge;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    std::array<int, 3> crossing{};
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (negative(side, a) != negative(side, b))
        crossing[static_cast<size_t>(count++)] = index_of(edge_key(a, b));
    }
    if (count != 2) continue;
    cut.segments.push_back({f, crossing[0], crossing[1]});
    labels.parent[static_cast<size_t>(labels.find(crossing[0]))] = labels.find(crossing[1]);
  }
  // Loop labels 0 … num_loops − 1 in the order of the edges' first appearance.
  std::map<int, int> number;
  cut.loop.resize(cut.edges.size());
  for (size_t i = 0; i < cut.edges.size(); ++i) {
    const auto [it, added] =
        number.emplace(labels.find(static_cast<int>(i)), static_cast<int>(number.size()));
    cut.loop[i] = it->second;
  }
  cut.num_loops = static_cast<int>(number.size());
  std::vector<int> degree(cut.edges.size(), 0);
  for (const auto& s : cut.segments) {
    ++degree[static_cast<size_t>(s.a)];
    ++degree[static_cast<size_t>(s.b)];
  }
  cut.closed.assign(static_cast<size_t>(cut.num_loops), 1);
  for (size_t i = 0; i < cut.edges.size(); ++i)
    if (degree[i] != 2) cut.closed[static_cast<size_t>(cut.loop[i])] = 0;
  return cut;
}

Vec3 crossing_point(const TriMesh& mesh, const PlaneCut& cut, int i) {
  const auto [a, b] = cut.edges[static_cast<size_t>(i)];
  const double t = cut.t[static_cast<size_t>(i)];
  return (1.0 - t) * mesh.vertices.row(a).transpose() + t * mesh.vertices.row(b).transpose();
}

NearestCutLoop nearest_cut_loop(const TriMesh& mesh, const PlaneCut& cut, const Vec3& point,
                                const Vec3& normal) {
  // The crossing points, in plane coordinates around `point`.
  const Vec3 n = normal.normalized(), u = n.unitOrthogonal(), v_axis = n.cross(u);
  const size_t ne = cut.edges.size();
  std::vector<Eigen::Vector2d> crossing(ne);
  std::vector<double> distance(ne);
  for (size_t i = 0; i < ne; ++i) {
    const Vec3 x = crossing_point(mesh, cut, static_cast<int>(i)) - point;
    crossing[i] = Eigen::Vector2d(u.dot(x), v_axis.dot(x));
    distance[i] = x.norm();
  }
  // Which loops go around the point: a ray from it along u crosses an odd number of
  // their segments.
  std::vector<int> ray_crossings(static_cast<size_t>(cut.num_loops), 0);
  for (const auto& s : cut.segments) {
    const Eigen::Vector2d p = crossing[static_cast<size_t>(s.a)],
                          q = crossing[static_cast<size_t>(s.b)];
    if ((p.y() > 0.0) != (q.y() > 0.0) &&
        p.x() + (q.x() - p.x()) * (0.0 - p.y()) / (q.y() - p.y()) > 0.0)
      ++ray_crossings[static_cast<size_t>(cut.loop[static_cast<size_t>(s.a)])];
  }
  NearestCutLoop nearest;
  nearest.distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < ne; ++i) {
    const int loop = cut.loop[i];
    const bool encloses = ray_crossings[static_cast<size_t>(loop)] % 2 == 1;
    if ((encloses && !nearest.encloses) ||
        (encloses == nearest.encloses && distance[i] < nearest.distance))
      nearest = {loop, encloses, distance[i]};
  }
  if (nearest.loop < 0) nearest.distance = 0.0;
  return nearest;
}

double cut_loop_length(const TriMesh& mesh, const PlaneCut& cut, int loop) {
  double length = 0.0;
  for (const auto& s : cut.segments)
    if (cut.loop[static_cast<size_t>(s.a)] == loop)
      length += (crossing_point(mesh, cut, s.b) - crossing_point(mesh, cut, s.a)).norm();
  return length;
}

BeyondLoop beyond_nearest_loop(const TriMesh& mesh, const std::vector<double>& side,
                               const Vec3& point, const Vec3& normal, const std::string& source) {
  const int nv = mesh.num_vertices();
  const PlaneCut cut = cut_by_plane(mesh, side);
  if (cut.edges.empty()) throw InputError(source, "the plane misses the surface");
  const int nearest_loop = nearest_cut_loop(mesh, cut, point, normal).loop;
  BeyondLoop out;
  for (size_t i = 0; i < cut.edges.size(); ++i)
    if (cut.loop[i] == nearest_loop) out.loop_edges.push_back(cut.edges[i]);
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
      throw InputError(source,
                       "the cut loop nearest the point does not separate the surface "
                       "(the surface has a handle through it)");
  return out;
}

}  // namespace tightfit
