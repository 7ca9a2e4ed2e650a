#pragma once
/// Small meshes and random states shared by the physics tests.
#include <Eigen/Geometry>
#include <random>

#include "tightfit/common/types.hpp"

namespace tightfit::test {

/// Unit cube [0,1]³ split into 6 positively oriented tets around the diagonal 0-7.
inline void unit_cube_tets(Points3& rest, Tetrahedra& tets) {
  rest.resize(8, 3);
  for (int i = 0; i < 8; ++i) rest.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  tets.resize(6, 4);
  tets << 0, 1, 3, 7, 0, 3, 2, 7, 0, 2, 6, 7, 0, 6, 4, 7, 0, 4, 5, 7, 0, 5, 1, 7;
}

/// Row-major points as a flat vector (x0, y0, z0, x1, ...).
template <typename Points>
Eigen::VectorXd flatten(const Points& p) {
  return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
}

/// Uniform random number in [lo, hi].
inline double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A random rotation (unit quaternion from a seeded generator).
inline Mat3 random_rotation(unsigned seed) {
  std::mt19937 rng(seed);
  Eigen::Quaterniond q(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1),
                       uniform(rng, -1, 1));
  q.normalize();
  return q.toRotationMatrix();
}

}  // namespace tightfit::test
