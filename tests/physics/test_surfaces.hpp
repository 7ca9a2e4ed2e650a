#pragma once
/// Triangulated cylinders and spheres for the shape-operator and pressure tests.
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "tightfit/common/types.hpp"

namespace tightfit::test {

/// A (θ, z) grid on the cylinder x² + y² = R², z in [0, L], θ in [0, span]. Pattern
/// vertices are the grid nodes; with span = 2π the last column is a seam copy of the
/// first and both map to the same garment vertex.
struct CylinderMesh {
  Points2 param;                       ///< per pattern vertex (θ, z)
  Triangles pattern_faces;             ///< over pattern vertices, counter-clockwise in (θ, z)
  std::vector<int> to_garment;         ///< pattern vertex → garment vertex
  Points3 garment;                     ///< n_g×3 positions on the cylinder
  Triangles garment_faces;             ///< counter-clockwise seen from outside
  std::vector<bool> boundary_garment;  ///< garment vertex on the mesh boundary
};

/// `jitter` moves interior nodes by up to that fraction of the grid spacing (in θ and
/// z); `random_diagonals` splits each quad along a random diagonal (irregular valences).
inline CylinderMesh cylinder_mesh(double R, double L, double span, int n_theta, int n_z,
                                  double jitter, bool random_diagonals, unsigned seed) {
  const double two_pi = 2.0 * M_PI;
  const bool closed = std::abs(span - two_pi) < 1e-12;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int cols = n_theta + 1, rows = n_z + 1;
  const int garment_cols = closed ? n_theta : cols;
  CylinderMesh m;
  m.param.resize(cols * rows, 2);
  m.to_garment.resize(cols * rows);
  const double dt = span / n_theta, dz = L / n_z;
  std::vector<Vec2> offset(garment_cols * rows, Vec2::Zero());
  for (int j = 1; j < n_z; ++j)
    for (int i = closed ? 0 : 1; i < n_theta; ++i)
      offset[i + garment_cols * j] = Vec2(jitter * dt * u(rng), jitter * dz * u(rng));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const int p = i + cols * j;
      const int g = (closed ? i % n_theta : i) + garment_cols * j;
      m.to_garment[p] = g;
      m.param.row(p) = (Vec2(i * dt, j * dz) + offset[g]).transpose();
    }
  m.garment.resize(garment_cols * rows, 3);
  m.boundary_garment.assign(garment_cols * rows, false);
  for (int p = 0; p < cols * rows; ++p) {
    const double th = m.param(p, 0), z = m.param(p, 1);
    m.garment.row(m.to_garment[p]) << R * std::cos(th), R * std::sin(th), z;
    const int i = p % cols, j = p / cols;
    if (j == 0 || j == n_z || (!closed && (i == 0 || i == n_theta)))
      m.boundary_garment[m.to_garment[p]] = true;
  }
  m.pattern_faces.resize(2 * n_theta * n_z, 3);
  int f = 0;
  for (int j = 0; j < n_z; ++j)
    for (int i = 0; i < n_theta; ++i) {
      const int a = i + cols * j, b = a + 1, c = a + 1 + cols, d = a + cols;
      if (random_diagonals && u(rng) < 0.0) {
        m.pattern_faces.row(f++) << a, b, d;
        m.pattern_faces.row(f++) << b, c, d;
      } else {
        m.pattern_faces.row(f++) << a, b, c;
        m.pattern_faces.row(f++) << a, c, d;
      }
    }
  m.garment_faces.resize(m.pattern_faces.rows(), 3);
  for (int e = 0; e < m.pattern_faces.rows(); ++e)
    for (int k = 0; k < 3; ++k) m.garment_faces(e, k) = m.to_garment[m.pattern_faces(e, k)];
  return m;
}

/// Icosphere of radius R: the icosahedron subdivided `levels` times, vertices projected
/// onto the sphere, faces counter-clockwise seen from outside; `jitter` > 0 moves the
/// vertices randomly on the sphere by up to that fraction of the edge length.
inline void icosphere(double R, int levels, Points3& vertices, Triangles& faces,
                      double jitter = 0.0, unsigned seed = 1) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]),
                ca = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  if (jitter > 0.0) {
    // Move each vertex tangentially by up to `jitter` times the edge length, reproject.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double edge = (v[f[0][1]] - v[f[0][0]]).norm();
    for (auto& p : v) p = (p + jitter * edge * Vec3(u(rng), u(rng), u(rng))).normalized();
  }
  vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    vertices.row(static_cast<Eigen::Index>(i)) = R * v[i].transpose();
  faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
}

}  // namespace tightfit::test
