#pragma once
/// Closed control meshes for the subdiv tests, with the valences the limit surface has
/// to handle (3..6), and small mesh utilities shared by those tests.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "support/test_meshes.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit::subdiv_test {

/// A uniformly random point of a random face (barycentric u, v with u + v ≤ 1).
inline SurfacePoint random_point(std::mt19937& rng, int num_faces) {
  std::uniform_int_distribution<int> face(0, num_faces - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double u = unit(rng), v = unit(rng);
  if (u + v > 1) u = 1 - u, v = 1 - v;
  return {face(rng), u, v};
}

/// Turns every face so that its normal points away from the origin (convex meshes around 0).
inline void orient_outward(TriMesh& m) {
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 a = m.vertices.row(m.faces(f, 0)).transpose();
    const Vec3 b = m.vertices.row(m.faces(f, 1)).transpose();
    const Vec3 c = m.vertices.row(m.faces(f, 2)).transpose();
    if ((b - a).cross(c - a).dot(a + b + c) < 0.0) std::swap(m.faces(f, 1), m.faces(f, 2));
  }
}

inline TriMesh make_mesh(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& f) {
  TriMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    m.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      m.faces(static_cast<Eigen::Index>(i), k) = f[i][static_cast<std::size_t>(k)];
  }
  orient_outward(m);
  return m;
}

/// Regular icosahedron with unit circumradius: 12 vertices of valence 5 (outward faces).
using ::tightfit::test::icosahedron;

/// Regular tetrahedron: 4 vertices of valence 3.
inline TriMesh tetrahedron() {
  return make_mesh({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}},
                   {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}});
}

/// Octahedron with unit circumradius: 6 vertices of valence 4.
inline TriMesh octahedron() {
  return make_mesh(
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

/// Cube [-1,1]³ split into triangles with diagonals chosen so that the corners have
/// valences 6, 3, 4, 5, 4, 5, 4, 5 (vertex index = x + 2y + 4z).
inline TriMesh triangulated_cube() {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
  // Each quad (a,b,c,d) in cyclic order is split along the diagonal a-c.
  const std::vector<std::array<int, 4>> quads = {{0, 2, 6, 4}, {0, 1, 5, 4}, {0, 1, 3, 2},
                                                 {3, 1, 5, 7}, {7, 3, 2, 6}, {7, 5, 4, 6}};
  std::vector<std::array<int, 3>> f;
  for (const auto& q : quads) {
    f.push_back({q[0], q[1], q[2]});
    f.push_back({q[0], q[2], q[3]});
  }
  return make_mesh(v, f);
}

/// One 1-to-4 split of every face with new vertices at edge midpoints (no smoothing):
/// the old vertices keep their valence, new ones have valence 6.
inline TriMesh midpoint_subdivide(const TriMesh& m) {
  std::vector<Vec3> v;
  for (int i = 0; i < m.num_vertices(); ++i) v.push_back(m.vertices.row(i).transpose());
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    v.push_back(0.5 * (v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]));
    const int id = static_cast<int>(v.size()) - 1;
    mid.emplace(key, id);
    return id;
  };
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < m.num_faces(); ++i) {
    const int a = m.faces(i, 0), b = m.faces(i, 1), c = m.faces(i, 2);
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    f.push_back({a, ab, ca});
    f.push_back({ab, b, bc});
    f.push_back({ca, bc, c});
    f.push_back({ab, bc, ca});
  }
  return make_mesh(v, f);
}

/// Moves every vertex by a uniform random offset in [-amplitude, amplitude]³.
inline TriMesh perturbed(TriMesh m, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  for (int i = 0; i < m.num_vertices(); ++i) {
    for (int k = 0; k < 3; ++k) m.vertices(i, k) += d(rng);
  }
  return m;
}

/// The test meshes: all closed, with extraordinary vertices of valence 3, 4, 5 and
/// regular faces (after a midpoint split) next to irregular ones.
inline std::vector<std::pair<const char*, TriMesh>> irregular_meshes() {
  return {{"icosahedron", icosahedron()},
          {"subdivided_octahedron", midpoint_subdivide(octahedron())},
          {"subdivided_cube", midpoint_subdivide(triangulated_cube())},
          {"perturbed_cube", perturbed(midpoint_subdivide(triangulated_cube()), 0.15, 7)}};
}

/// Distance of (u,v) to the nearest line of the dyadic grid of depth `depth` (lines
/// u = i/2^depth, v = j/2^depth, u+v = k/2^depth), measured in u or v.
inline double distance_to_dyadic_lines(double u, double v, int depth) {
  const double n = std::ldexp(1.0, depth);
  auto frac_dist = [n](double t) {
    const double x = t * n;
    return std::abs(x - std::round(x)) / n;
  };
  return std::min({frac_dist(u), frac_dist(v), frac_dist(u + v)});
}

/// Random point of a random face, at least `margin` away (in u, v) from every line of
/// the depth-`depth` dyadic grid (so that finite differences stay inside one polynomial
/// patch) and outside the Gregory corner regions of size 2^-depth.
inline SurfacePoint random_smooth_point(std::mt19937& rng, int num_faces, int depth,
                                        double margin) {
  std::uniform_int_distribution<int> face(0, num_faces - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double corner = std::ldexp(1.0, -depth);
  for (;;) {
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    if (u + v < corner + margin || u > 1.0 - corner - margin || v > 1.0 - corner - margin) continue;
    if (distance_to_dyadic_lines(u, v, depth) < margin) continue;
    return {face(rng), u, v};
  }
}

}  // namespace tightfit::subdiv_test
