#pragma once
/// An independent reference for the Loop limit surface: uniform Loop subdivision of a
/// closed triangle mesh (Loop 1987 weights) and the limit-position mask, with the base
/// face and (u,v) that every refined vertex corresponds to. Refined vertices sit at
/// dyadic (u,v) of the base faces, where the exact limit point is given by the mask.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "tightfit/geometry/mesh.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit::subdiv_test {

/// Loop's vertex weight β(n): v' = (1 - nβ) v + β Σ neighbours.
inline double loop_beta(int n) {
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * std::numbers::pi / n);
  return (5.0 / 8.0 - c * c) / n;
}

struct LoopLevel {
  TriMesh mesh;
  /// Per face: the base face it descends from and the (u,v) of its three corners there.
  std::vector<int> base_face;
  std::vector<std::array<Vec2, 3>> corner_uv;
};

inline LoopLevel loop_base(const TriMesh& m) {
  LoopLevel l{m, {}, {}};
  for (int f = 0; f < m.num_faces(); ++f) {
    l.base_face.push_back(f);
    l.corner_uv.push_back({Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)});
  }
  return l;
}

/// One step of Loop subdivision (closed meshes only).
inline LoopLevel loop_subdivide(const LoopLevel& in) {
  const TriMesh& m = in.mesh;
  const int nv = m.num_vertices();
  std::vector<std::vector<int>> neighbors(static_cast<std::size_t>(nv));
  std::map<std::pair<int, int>, std::vector<int>> edge_opposite;  // edge → opposite vertices
  for (int f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces(f, k), b = m.faces(f, (k + 1) % 3), c = m.faces(f, (k + 2) % 3);
      edge_opposite[std::minmax(a, b)].push_back(c);
      auto& na = neighbors[static_cast<std::size_t>(a)];
      if (std::find(na.begin(), na.end(), b) == na.end()) na.push_back(b);
      auto& nb = neighbors[static_cast<std::size_t>(b)];
      if (std::find(nb.begin(), nb.end(), a) == nb.end()) nb.push_back(a);
    }
  }
  std::vector<Vec3> out;
  for (int i = 0; i < nv; ++i) {
    const auto& nb = neighbors[static_cast<std::size_t>(i)];
    const int n = static_cast<int>(nb.size());
    const double beta = loop_beta(n);
    Vec3 x = (1.0 - n * beta) * m.vertices.row(i).transpose();
    for (int j : nb) x += beta * m.vertices.row(j).transpose();
    out.push_back(x);
  }
  std::map<std::pair<int, int>, int> edge_vertex;
  for (const auto& [e, opp] : edge_opposite) {
    const Vec3 x = 0.375 * (m.vertices.row(e.first) + m.vertices.row(e.second)).transpose() +
                   0.125 * (m.vertices.row(opp.at(0)) + m.vertices.row(opp.at(1))).transpose();
    edge_vertex[e] = static_cast<int>(out.size());
    out.push_back(x);
  }
  LoopLevel l;
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < m.num_faces(); ++f) {
    const int a = m.faces(f, 0), b = m.faces(f, 1), c = m.faces(f, 2);
    const int ab = edge_vertex.at(std::minmax(a, b)), bc = edge_vertex.at(std::minmax(b, c)),
              ca = edge_vertex.at(std::minmax(c, a));
    const auto& uv = in.corner_uv[static_cast<std::size_t>(f)];
    const Vec2 uab = 0.5 * (uv[0] + uv[1]), ubc = 0.5 * (uv[1] + uv[2]),
               uca = 0.5 * (uv[2] + uv[0]);
    faces.push_back({a, ab, ca});
    l.corner_uv.push_back({uv[0], uab, uca});
    faces.push_back({ab, b, bc});
    l.corner_uv.push_back({uab, uv[1], ubc});
    faces.push_back({ca, bc, c});
    l.corner_uv.push_back({uca, ubc, uv[2]});
    faces.push_back({ab, bc, ca});
    l.corner_uv.push_back({uab, ubc, uca});
    for (int k = 0; k < 4; ++k) l.base_face.push_back(in.base_face[static_cast<std::size_t>(f)]);
  }
  l.mesh.vertices.resize(static_cast<Eigen::Index>(out.size()), 3);
  for (std::size_t i = 0; i < out.size(); ++i)
    l.mesh.vertices.row(static_cast<Eigen::Index>(i)) = out[i].transpose();
  l.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      l.mesh.faces(static_cast<Eigen::Index>(i), k) = faces[i][static_cast<std::size_t>(k)];
  }
  return l;
}

/// Limit positions of all vertices of a closed mesh: (1 - nχ) v + χ Σ neighbours with
/// χ = 1 / (n + 3 / (8β(n))).
inline Points3 loop_limit_positions(const TriMesh& m) {
  std::vector<std::vector<int>> neighbors(static_cast<std::size_t>(m.num_vertices()));
  for (int f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces(f, k), b = m.faces(f, (k + 1) % 3);
      auto& na = neighbors[static_cast<std::size_t>(a)];
      if (std::find(na.begin(), na.end(), b) == na.end()) na.push_back(b);
    }
  }
  Points3 limit(m.num_vertices(), 3);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const auto& nb = neighbors[static_cast<std::size_t>(i)];
    const int n = static_cast<int>(nb.size());
    const double chi = 1.0 / (n + 3.0 / (8.0 * loop_beta(n)));
    Vec3 x = (1.0 - n * chi) * m.vertices.row(i).transpose();
    for (int j : nb) x += chi * m.vertices.row(j).transpose();
    limit.row(i) = x.transpose();
  }
  return limit;
}

/// A base-face surface point for every vertex of a refined level (from any face using it).
inline std::vector<SurfacePoint> vertex_surface_points(const LoopLevel& l) {
  std::vector<SurfacePoint> s(static_cast<std::size_t>(l.mesh.num_vertices()));
  for (int f = 0; f < l.mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Vec2& uv = l.corner_uv[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
      s[static_cast<std::size_t>(l.mesh.faces(f, k))] = {l.base_face[static_cast<std::size_t>(f)],
                                                         uv[0], uv[1]};
    }
  }
  return s;
}

}  // namespace tightfit::subdiv_test
