#include "tightfit/objectives/directional_stretch_objective.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::directional_stretch_objective_test {

/// A flat square grid piece (side 0.1 m) with grain `grain`, mapped to 3D by
/// x = R diag(s1, s2) X (s1 along the piece's x axis, s2 along its y axis).
test::GarmentState stretched_square(double s1, double s2, Vec2 grain, double jitter = 0.0) {
  Pattern pattern;
  pattern.pieces.push_back(test::grid_piece(4, 4, 0.1, 0.1, jitter, 3));
  pattern.pieces[0].grain = grain;
  test::GarmentState s{weld_pattern(pattern), VecX()};
  const Mat3 rot = Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  s.x.resize(3 * s.garment.num_garment_vertices());
  const Points2 rest = s.garment.rest_positions();
  for (int p = 0; p < rest.rows(); ++p)
    s.x.segment<3>(3 * s.garment.topology->pattern_to_garment[p]) =
        rot * Vec3(s1 * rest(p, 0), s2 * rest(p, 1), 0.0) + Vec3(0.2, -0.1, 0.3);
  return s;
}

TEST(DirectionalStretchObjective, AcrossAndAlongTheGrainByHand) {
  // Grain along the piece's y axis: across the grain is x (stretch 1.4), along is y (1.0).
  const test::GarmentState s = stretched_square(1.4, 1.0, Vec2::UnitY());
  const Points2 rest = s.garment.rest_positions();
  const DirectionalStretchObjective across(s.garment, FabricDirection::kAcrossGrain, {1.1, 1.3});
  const DirectionalStretchObjective along(s.garment, FabricDirection::kAlongGrain, {1.1, 1.3});
  EXPECT_DOUBLE_EQ(across.squared_min(), 1.21);
  EXPECT_DOUBLE_EQ(across.squared_max(), 1.69);
  // Area 0.01 m².
  EXPECT_NEAR(across.value({s.x, rest}), 0.01 * std::pow(1.96 - 1.69, 2), 1e-14);
  EXPECT_NEAR(along.value({s.x, rest}), 0.01 * std::pow(1.0 - 1.21, 2), 1e-14);
  for (double st : across.stretches({s.x, rest})) EXPECT_NEAR(st, 1.4, 1e-12);
  for (double st : along.stretches({s.x, rest})) EXPECT_NEAR(st, 1.0, 1e-12);
  // Inside the range along the measured direction: zero value and gradient, whatever the
  // other direction does.
  const test::GarmentState in = stretched_square(1.2, 0.8, Vec2::UnitY());
  EXPECT_EQ(across.value({in.x, rest}), 0.0);
  VecX dx = VecX::Zero(in.x.size()), dr = VecX::Zero(rest.size());
  across.add_gradient({in.x, rest}, dx, dr);
  EXPECT_EQ(dx.norm() + dr.norm(), 0.0);
}

TEST(DirectionalStretchObjective, FollowsARotatedGrain) {
  // Grain at 45°: a stretch of 1.4 along x and 1.0 along y gives a squared stretch
  // (1.96 + 1)/2 = 1.48 along both the grain and across it.
  const Vec2 grain = Vec2(1.0, 1.0).normalized();
  const test::GarmentState s = stretched_square(1.4, 1.0, 3.0 * grain);
  const Points2 rest = s.garment.rest_positions();
  for (FabricDirection dir : {FabricDirection::kAlongGrain, FabricDirection::kAcrossGrain}) {
    const DirectionalStretchObjective t(s.garment, dir, {1.3, 1.3});
    for (double st : t.stretches({s.x, rest})) EXPECT_NEAR(st * st, 1.48, 1e-12);
    EXPECT_NEAR(t.value({s.x, rest}), 0.01 * std::pow(1.48 - 1.69, 2), 1e-14);
  }
}

TEST(DirectionalStretchObjective, GradientsOnRandomStates) {
  test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, 0.1, 0.2, 4);
  s.garment.pattern.pieces[0].grain = Vec2(0.3, 1.0).normalized();
  for (FabricDirection dir : {FabricDirection::kAlongGrain, FabricDirection::kAcrossGrain}) {
    const DirectionalStretchObjective t(s.garment, dir, {1.05, 1.15});
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
}

TEST(DirectionalStretchObjective, GradientsAtAnExactTargetStretch) {
  // min = max: the penalty is (c − c0)², smooth through the target.
  const test::GarmentState s = stretched_square(1.3 * (1.0 + 1e-4), 1.1, Vec2::UnitY(), 0.2);
  const DirectionalStretchObjective t(s.garment, FabricDirection::kAcrossGrain, {1.3, 1.3});
  const Points2 rest = s.garment.rest_positions();
  EXPECT_GT(t.value({s.x, rest}), 0.0);
  const test::GradientErrors e = test::gradient_errors(t, s.x, rest, 1e-9, 1e-9);
  EXPECT_LT(e.x, 1e-6);
  EXPECT_LT(e.rest, 1e-6);
}

TEST(DirectionalStretchObjective, UnboundedAboveAndBadInput) {
  const test::GarmentState st = stretched_square(3.0, 1.2, Vec2::UnitY());
  const DirectionalStretchObjective t(st.garment, FabricDirection::kAcrossGrain,
                                      {1.0, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(t.value({st.x, st.garment.rest_positions()}), 0.0);
  EXPECT_THROW(DirectionalStretchObjective(st.garment, FabricDirection::kAlongGrain, {1.3, 1.1}),
               InputError);
  EXPECT_THROW(DirectionalStretchObjective(st.garment, FabricDirection::kAlongGrain, {0.0, 1.1}),
               InputError);
  Garment no_grain = st.garment;
  no_grain.pattern.pieces[0].grain = Vec2::Zero();
  EXPECT_THROW(DirectionalStretchObjective(no_grain, FabricDirection::kAlongGrain, {1.0, 1.1}),
               InputError);
}

}  // namespace tightfit::directional_stretch_objective_test
