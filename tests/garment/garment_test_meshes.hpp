#pragma once
/// Small surfaces built in code for the garment tests.
#include <cmath>
#include <numbers>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit::test {

inline constexpr double kPi = std::numbers::pi;

/// Open cylinder around the y axis: `rings` rings of `segments` vertices from y = 0 to
/// y = length, each quad split into two triangles, normals outward. Every quad is a
/// planar rectangle, so the polyhedron is exactly developable.
inline TriMesh open_cylinder(double radius, double length, int segments, int rings,
                             double phase = 0.0) {
  TriMesh m;
  m.vertices.resize(segments * rings, 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double a = phase + 2.0 * kPi * s / segments;
      m.vertices.row(r * segments + s) << radius * std::cos(a), length * r / (rings - 1),
          -radius * std::sin(a);
    }
  m.faces.resize(2 * segments * (rings - 1), 3);
  int f = 0;
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  return m;
}

/// The open cylinder closed by two flat fans (a closed, outward-oriented body surface).
inline TriMesh closed_cylinder(double radius, double length, int segments, int rings,
                               double phase = 0.0) {
  TriMesh side = open_cylinder(radius, length, segments, rings, phase);
  const int n = side.num_vertices();
  TriMesh m;
  m.vertices.resize(n + 2, 3);
  m.vertices.topRows(n) = side.vertices;
  m.vertices.row(n) << 0, 0, 0;
  m.vertices.row(n + 1) << 0, length, 0;
  m.faces.resize(side.num_faces() + 2 * segments, 3);
  m.faces.topRows(side.num_faces()) = side.faces;
  int f = side.num_faces();
  const int top = (rings - 1) * segments;
  for (int s = 0; s < segments; ++s) {
    const int s1 = (s + 1) % segments;
    m.faces.row(f++) << n, s1, s;                  // bottom, normal −y
    m.faces.row(f++) << n + 1, top + s, top + s1;  // top, normal +y
  }
  return m;
}

/// Geodesic sphere: icosahedron with each face split into k² triangles, projected.
/// Two closed cylinders (closed_cylinder(0.05, 0.4, 32, 17)), the second moved by
/// 0.3 m along x: one surface of two separate parts.
inline TriMesh two_cylinders() {
  const TriMesh one = closed_cylinder(0.05, 0.4, 32, 17);
  TriMesh two;
  two.vertices.resize(2 * one.num_vertices(), 3);
  two.vertices << one.vertices, one.vertices.rowwise() + Eigen::RowVector3d(0.3, 0.0, 0.0);
  two.faces.resize(2 * one.num_faces(), 3);
  two.faces << one.faces, one.faces.array() + one.num_vertices();
  return two;
}

inline TriMesh geodesic_sphere(double radius, int k) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Points3 ico(12, 3);
  ico << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t,  //
      t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1;
  const int F[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  std::vector<Vec3> verts;
  std::vector<std::array<int, 3>> faces;
  auto add = [&](const Vec3& p) {
    const Vec3 q = radius * p.normalized();
    for (size_t i = 0; i < verts.size(); ++i)
      if ((verts[i] - q).norm() < 1e-9 * radius) return static_cast<int>(i);
    verts.push_back(q);
    return static_cast<int>(verts.size()) - 1;
  };
  for (const auto& f : F) {
    const Vec3 a = ico.row(f[0]), b = ico.row(f[1]), c = ico.row(f[2]);
    std::vector<std::vector<int>> id(k + 1);
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j <= k - i; ++j)
        id[i].push_back(add(a + (b - a) * i / double(k) + (c - a) * j / double(k)));
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k - i; ++j) {
        faces.push_back({id[i][j], id[i + 1][j], id[i][j + 1]});
        if (j + 1 < k - i) faces.push_back({id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]});
      }
  }
  TriMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i)
    m.vertices.row(static_cast<Eigen::Index>(i)) = verts[i].transpose();
  m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i)
    m.faces.row(static_cast<Eigen::Index>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return m;
}

}  // namespace tightfit::test
