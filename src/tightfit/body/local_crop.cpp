#include "tightfit/body/local_crop.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/geometry/plane_loops.hpp"

namespace tightfit {
namespace {

using Edge = std::pair<int, int>;  // (smaller, larger) vertex index

Edge edge_key(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

/// Triangulates the simple polygon `loop` (indices into `points`, counter-clockwise) by
/// ear clipping, always clipping the ear with the largest smallest angle.
std::vector<std::array<int, 3>> triangulate_polygon(std::vector<int> loop,
                                                    const std::vector<Eigen::Vector2d>& points,
                                                    const std::string& source) {
  std::vector<std::array<int, 3>> triangles;
  auto min_angle = [&](int a, int b, int c) {
    const std::array<Eigen::Vector2d, 3> p{points[a], points[b], points[c]};
    double smallest = 180.0;
    for (int k = 0; k < 3; ++k)
      smallest =
          std::min(smallest, angle_between_deg(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]));
    return smallest;
  };
  while (loop.size() > 3) {
    const size_t n = loop.size();
    int best = -1;
    double best_angle = -1.0;
    for (size_t i = 0; i < n; ++i) {
      const int a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
      if (signed_area(points[a], points[b], points[c]) <= 0.0) continue;  // reflex or flat
      bool empty = true;
      for (size_t j = 0; j < n && empty; ++j) {
        const int q = loop[j];
        if (q == a || q == b || q == c) continue;
        empty = !(signed_area(points[a], points[b], points[q]) >= 0.0 &&
                  signed_area(points[b], points[c], points[q]) >= 0.0 &&
                  signed_area(points[c], points[a], points[q]) >= 0.0);
      }
      if (!empty) continue;
      const double angle = min_angle(a, b, c);
      if (angle > best_angle) {
        best_angle = angle;
        best = static_cast<int>(i);
      }
    }
    if (best < 0)
      throw InputError(source,
                       "the cut loop is not a simple polygon in the plane; it cannot be capped");
    const size_t i = static_cast<size_t>(best);
    triangles.push_back({loop[(i + n - 1) % n], loop[i], loop[(i + 1) % n]});
    loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
  }
  triangles.push_back({loop[0], loop[1], loop[2]});
  return triangles;
}

}  // namespace

TriMesh crop_beyond_nearest_loop(const TriMesh& surface, const CropPlane& plane,
                                 const std::string& source) {
  const Vec3& n = plane.normal;
  if (!(n.norm() > 0.0) || !n.allFinite() || !plane.point.allFinite())
    throw InputError(source, "the normal must be a non-zero finite vector");
  const Vec3 unit = n.normalized();
  const int nv = surface.num_vertices();

  // Signed distances, with vertices (almost) on the plane pushed off it.
  Points3 vertices = surface.vertices;
  const Vec3 lo = vertices.colwise().minCoeff().transpose(),
             hi = vertices.colwise().maxCoeff().transpose();
  const double epsilon = 1e-7 * (hi - lo).norm();
  std::vector<double> side(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    const Vec3 x = vertices.row(v).transpose();
    double d = unit.dot(x - plane.point);
    if (std::abs(d) < epsilon) {
      const double pushed = d < 0.0 ? -epsilon : epsilon;
      vertices.row(v) = (x + (pushed - d) * unit).transpose();
      d = pushed;
    }
    side[static_cast<size_t>(v)] = d;
  }
  auto cut_point = [&](const Edge& e) -> Vec3 {
    const double da = side[static_cast<size_t>(e.first)], db = side[static_cast<size_t>(e.second)];
    const double t = da / (da - db);
    return (1.0 - t) * vertices.row(e.first).transpose() + t * vertices.row(e.second).transpose();
  };

  const BeyondLoop beyond = beyond_nearest_loop(surface, side, plane.point, unit, source);
  const std::vector<char>& removed = beyond.beyond;
  std::map<Edge, int> cut_vertex;  // crossed edge of the loop → new vertex index
  for (const Edge& e : beyond.loop_edges) cut_vertex.emplace(e, -1);

  // Kept vertices, renumbered, then the cut points.
  std::vector<int> new_index(static_cast<size_t>(nv), -1);
  std::vector<Vec3> out_vertices;
  for (int v = 0; v < nv; ++v)
    if (!removed[static_cast<size_t>(v)]) {
      new_index[static_cast<size_t>(v)] = static_cast<int>(out_vertices.size());
      out_vertices.push_back(vertices.row(v).transpose());
    }
  for (auto& [e, index] : cut_vertex) {
    index = static_cast<int>(out_vertices.size());
    out_vertices.push_back(cut_point(e));
  }

  std::vector<std::array<int, 3>> out_faces;
  std::map<int, int> cap_next;  // cap boundary: cut vertex → next cut vertex (cap orientation)
  for (int f = 0; f < surface.num_faces(); ++f) {
    std::vector<int> polygon;  // the kept part, counter-clockwise
    bool crossed = false;
    for (int k = 0; k < 3; ++k) {
      const int a = surface.faces(f, k), b = surface.faces(f, (k + 1) % 3);
      if (!removed[static_cast<size_t>(a)]) polygon.push_back(new_index[static_cast<size_t>(a)]);
      if (const auto it = cut_vertex.find(edge_key(a, b)); it != cut_vertex.end()) {
        polygon.push_back(it->second);
        crossed = true;
      }
    }
    if (!crossed) {
      if (polygon.size() == 3) out_faces.push_back({polygon[0], polygon[1], polygon[2]});
      continue;
    }
    // The kept polygon's new boundary edge runs from one cut vertex to the other; the
    // cap uses it reversed.
    const size_t m = polygon.size();
    const int first_cut =
        static_cast<int>(out_vertices.size()) - static_cast<int>(cut_vertex.size());
    for (size_t i = 0; i < m; ++i) {
      const int a = polygon[i], b = polygon[(i + 1) % m];
      if (a >= first_cut && b >= first_cut) cap_next[b] = a;
    }
    if (m == 3) {
      out_faces.push_back({polygon[0], polygon[1], polygon[2]});
    } else {  // a quad: split along its shorter diagonal
      const double d02 = (out_vertices[static_cast<size_t>(polygon[0])] -
                          out_vertices[static_cast<size_t>(polygon[2])])
                             .norm();
      const double d13 = (out_vertices[static_cast<size_t>(polygon[1])] -
                          out_vertices[static_cast<size_t>(polygon[3])])
                             .norm();
      if (d02 <= d13) {
        out_faces.push_back({polygon[0], polygon[1], polygon[2]});
        out_faces.push_back({polygon[0], polygon[2], polygon[3]});
      } else {
        out_faces.push_back({polygon[1], polygon[2], polygon[3]});
        out_faces.push_back({polygon[1], polygon[3], polygon[0]});
      }
    }
  }

  // The cap: the cut vertices in loop order, triangulated in the plane. Seen from the
  // removed side (against the normal) the loop runs counter-clockwise.
  if (cap_next.size() != cut_vertex.size())
    throw InputError(source, "the cut loop is not closed; the surface is not a closed 2-manifold");
  std::vector<int> loop{cap_next.begin()->first};
  while (true) {
    const int next = cap_next.at(loop.back());
    if (next == loop.front()) break;
    if (loop.size() > cap_next.size())
      throw InputError(source,
                       "the cut loop is not simple; the surface is not a closed 2-manifold");
    loop.push_back(next);
  }
  if (loop.size() != cap_next.size())
    throw InputError(source, "the cut loop is not simple; the surface is not a closed 2-manifold");
  const Vec3 u = unit.unitOrthogonal(), w = -unit.cross(u);  // u × w = −normal
  std::vector<Eigen::Vector2d> planar(out_vertices.size());
  for (int v : loop) {
    const Vec3 x = out_vertices[static_cast<size_t>(v)] - plane.point;
    planar[static_cast<size_t>(v)] = Eigen::Vector2d(u.dot(x), w.dot(x));
  }
  const double area = polygon_signed_area(
      loop.size(), [&](size_t i) { return planar[static_cast<size_t>(loop[i])]; });
  if (!(area > 0.0))
    throw InputError(
        source,
        "the cut loop winds the wrong way around the normal; is the surface outward-oriented?");
  for (const auto& t : triangulate_polygon(loop, planar, source)) out_faces.push_back(t);

  TriMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(out_vertices.size()), 3);
  for (size_t i = 0; i < out_vertices.size(); ++i)
    out.vertices.row(static_cast<Eigen::Index>(i)) = out_vertices[i].transpose();
  out.faces.resize(static_cast<Eigen::Index>(out_faces.size()), 3);
  for (size_t i = 0; i < out_faces.size(); ++i)
    for (int k = 0; k < 3; ++k)
      out.faces(static_cast<Eigen::Index>(i), k) = out_faces[i][static_cast<size_t>(k)];
  return out;
}

}  // namespace tightfit
