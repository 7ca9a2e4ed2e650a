#include "tightfit/objectives/stretch_objective.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::stretch_objective_test {

/// A flat square grid piece (side 0.1 m) mapped to 3D by x = R diag(s1, s2) X.
test::GarmentState stretched_square(double s1, double s2, double jitter = 0.0) {
  Pattern pattern;
  pattern.pieces.push_back(test::grid_piece(4, 4, 0.1, 0.1, jitter, 3));
  test::GarmentState s{weld_pattern(pattern), VecX()};
  const Mat3 rot = Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  s.x.resize(3 * s.garment.num_garment_vertices());
  const Points2 rest = s.garment.rest_positions();
  for (int p = 0; p < rest.rows(); ++p)
    s.x.segment<3>(3 * s.garment.topology->pattern_to_garment[p]) =
        rot * Vec3(s1 * rest(p, 0), s2 * rest(p, 1), 0.0) + Vec3(0.2, -0.1, 0.3);
  return s;
}

TEST(StretchObjective, UniformlyStretchedSquareByHand) {
  const test::GarmentState s = stretched_square(1.4, 1.0);
  const StretchObjective t(s.garment, {1.1, 1.3});
  EXPECT_DOUBLE_EQ(t.lambda_min(), 1.21);
  EXPECT_DOUBLE_EQ(t.lambda_max(), 1.69);
  const Points2 rest = s.garment.rest_positions();
  // Area 0.01 m²; λ1 = 1.96 above 1.69, λ2 = 1 below 1.21.
  const double expected = 0.01 * (std::pow(1.96 - 1.69, 2) + std::pow(1.0 - 1.21, 2));
  EXPECT_NEAR(t.value({s.x, rest}), expected, 1e-14);
  for (const Vec2& ev : t.cauchy_green_eigenvalues({s.x, rest})) {
    EXPECT_NEAR(ev[0], 1.96, 1e-12);
    EXPECT_NEAR(ev[1], 1.0, 1e-12);
  }
  // Inside the range: zero value and zero gradient.
  const test::GarmentState in = stretched_square(1.2, 1.15);
  EXPECT_EQ(t.value({in.x, rest}), 0.0);
  VecX dx = VecX::Zero(in.x.size()), dr = VecX::Zero(rest.size());
  t.add_gradient({in.x, rest}, dx, dr);
  EXPECT_EQ(dx.norm() + dr.norm(), 0.0);
}

TEST(StretchObjective, GradientsOnRandomStates) {
  test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, 0.1, 0.2, 4);
  const StretchObjective t(s.garment, {1.05, 1.15});
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const VecX x = test::perturb(s.x, 0.004, seed);
    const Points2 rest = test::perturb(s.garment.rest_positions(), 0.002, 10 + seed);
    const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
    EXPECT_GT(e.norm_x, 0.0);
    EXPECT_GT(e.norm_rest, 0.0);
    EXPECT_LT(e.x, 1e-6) << "seed " << seed;
    EXPECT_LT(e.rest, 1e-6) << "seed " << seed;
  }
}

TEST(StretchObjective, GradientsNearTheLowerBound) {
  // Isotropic stretch just below s_min: λ = λmin (1 − 1e-5) for both eigenvalues.
  const double smin = 1.1;
  const double s = smin * std::sqrt(1.0 - 1e-5);
  const test::GarmentState st = stretched_square(s, s, 0.2);
  const StretchObjective t(st.garment, {smin, 1.3});
  const Points2 rest = st.garment.rest_positions();
  EXPECT_GT(t.value({st.x, rest}), 0.0);
  const test::GradientErrors e = test::gradient_errors(t, st.x, rest, 1e-9, 1e-9);
  EXPECT_LT(e.x, 1e-6);
  EXPECT_LT(e.rest, 1e-6);
  // One eigenvalue just below, one just above λmin.
  const test::GarmentState mixed = stretched_square(smin * (1.0 + 1e-5), smin * (1.0 - 1e-5), 0.2);
  const test::GradientErrors m = test::gradient_errors(t, mixed.x, rest, 1e-9, 1e-9);
  EXPECT_LT(m.x, 1e-6);
  EXPECT_LT(m.rest, 1e-6);
}

TEST(StretchObjective, EqualEigenvaluesGiveFiniteExactGradients) {
  for (double s : {0.9, 1.5}) {  // both below and both above the range
    const test::GarmentState st = stretched_square(s, s, 0.0);
    const StretchObjective t(st.garment, {1.0, 1.2});
    const Points2 rest = st.garment.rest_positions();
    for (const Vec2& ev : t.cauchy_green_eigenvalues({st.x, rest}))
      EXPECT_NEAR(ev[0] - ev[1], 0.0, 1e-14);
    VecX dx = VecX::Zero(st.x.size()), dr = VecX::Zero(rest.size());
    t.add_gradient({st.x, rest}, dx, dr);
    EXPECT_TRUE(dx.allFinite() && dr.allFinite());
    const test::GradientErrors e = test::gradient_errors(t, st.x, rest, 1e-7, 1e-7);
    EXPECT_LT(e.x, 1e-6) << s;
    EXPECT_LT(e.rest, 1e-6) << s;
    // Nearly equal eigenvalues (gap ~1e-9).
    const test::GarmentState near = stretched_square(s * (1.0 + 1e-9), s, 0.0);
    const test::GradientErrors n = test::gradient_errors(t, near.x, rest, 1e-7, 1e-7);
    EXPECT_LT(n.x, 1e-6) << s;
    EXPECT_LT(n.rest, 1e-6) << s;
  }
}

TEST(StretchObjective, UnboundedAboveAndBadBounds) {
  const test::GarmentState st = stretched_square(3.0, 1.2);
  const StretchObjective t(st.garment, {1.0, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(t.value({st.x, st.garment.rest_positions()}), 0.0);
  EXPECT_THROW(StretchObjective(st.garment, {1.3, 1.1}), InputError);
  EXPECT_THROW(StretchObjective(st.garment, {0.0, 1.1}), InputError);
}

}  // namespace tightfit::stretch_objective_test
