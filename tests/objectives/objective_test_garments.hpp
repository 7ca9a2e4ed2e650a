#pragma once
/// Small garments with 3D states for the objective tests.
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "support/finite_difference.hpp"
#include "support/test_pieces.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit::test {

/// A garment and a 3D state of it.
struct GarmentState {
  Garment garment;
  VecX x;  // 3·n_g (m)
};

/// A sleeve: a grid piece of rest size (w, h) wrapped around the z axis at radius r, its
/// left and right sides sewn by one seam (a.vertices = right side, b = left side, both
/// bottom to top). The piece's x runs around the axis counter-clockwise, y along +z, so
/// the garment faces point outward. Pattern vertex (i, j) of the regular grid sits at
/// angle 2π i/(nx−1), height h j/(ny−1) (jittered interior vertices keep their grid slot).
inline GarmentState sleeve(int nx, int ny, double r, double w, double h, double jitter,
                           unsigned seed) {
  Pattern pattern;
  pattern.pieces.push_back(grid_piece(nx, ny, w, h, jitter, seed));
  Seam seam;
  seam.name = "axial seam";
  seam.a.piece = seam.b.piece = 0;
  for (int j = 0; j < ny; ++j) {
    seam.a.vertices.push_back(j * nx + nx - 1);
    seam.b.vertices.push_back(j * nx);
  }
  pattern.seams.push_back(seam);
  GarmentState s{weld_pattern(pattern), VecX()};
  s.x.resize(3 * s.garment.num_garment_vertices());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double a = 2.0 * std::numbers::pi * i / (nx - 1);
      s.x.segment<3>(3 * s.garment.topology->pattern_to_garment[j * nx + i]) =
          Vec3(r * std::cos(a), r * std::sin(a), h * j / (ny - 1));
    }
  return s;
}

/// Points with unit outward normals on a sphere (m points, about evenly spread: the
/// Fibonacci lattice), e.g. the sample of a shape target.
struct OrientedPoints {
  Points3 points;
  Points3 normals;
};

inline OrientedPoints fibonacci_sphere(const Vec3& centre, double radius, int m) {
  OrientedPoints out{Points3(m, 3), Points3(m, 3)};
  for (int k = 0; k < m; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / m, phi = k * 2.399963229728653;
    const Vec3 d(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    out.points.row(k) = (centre + radius * d).transpose();
    out.normals.row(k) = d.transpose();
  }
  return out;
}

/// x moved by up to `amount` (m) per coordinate, reproducibly.
inline VecX perturb(const VecX& x, double amount, unsigned seed) {
  return x + amount * random_vector(x.size(), seed);
}

/// Rest positions moved by up to `amount` (m) per coordinate, reproducibly.
inline Points2 perturb(const Points2& rest, double amount, unsigned seed) {
  const VecX d = random_vector(rest.size(), seed);
  return rest + amount * Eigen::Map<const Points2>(d.data(), rest.rows(), 2);
}

/// Relative errors of ∂T/∂x and ∂T/∂Xbar against fourth-order finite differences.
struct GradientErrors {
  double x = 0.0;
  double rest = 0.0;
  double norm_x = 0.0;
  double norm_rest = 0.0;
};

inline GradientErrors gradient_errors(const DesignTerm& term, const VecX& x, const Points2& rest,
                                      double hx, double hr) {
  VecX dx = VecX::Zero(x.size());
  VecX dr = VecX::Zero(rest.size());
  term.add_gradient(DesignState{x, rest}, dx, dr);
  GradientErrors e;
  e.norm_x = dx.norm();
  e.norm_rest = dr.norm();
  auto fx = [&](const VecX& y) { return term.value(DesignState{y, rest}); };
  e.x = check_gradient(fx, dx, x, hx).relative_error;
  auto fr = [&](const VecX& r) {
    const Points2 p = Eigen::Map<const Points2>(r.data(), rest.rows(), 2);
    return term.value(DesignState{x, p});
  };
  const VecX r0 = Eigen::Map<const VecX>(rest.data(), rest.size());
  e.rest = check_gradient(fr, dr, r0, hr).relative_error;
  return e;
}

}  // namespace tightfit::test
