#include "tightfit/objectives/seam_traction_objective.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "objectives/objective_test_garments.hpp"

namespace tightfit::seam_traction_objective_test {

TEST(SeamTractionObjective, UniformSleeveByHand) {
  // Regular sleeve: every quad is a planar rectangle, hoop stretch s (chord / rest
  // width), axial stretch 1, taut regime: S_xx = E/(1−ν²) e1 with e1 = (s²−1)/2, and the
  // seam normal is the pattern's x axis.
  const int nx = 17, ny = 6;
  const double r = 0.05, w = 0.9 * 2.0 * std::numbers::pi * r, h = 0.1;
  const test::GarmentState s = test::sleeve(nx, ny, r, w, h, 0.0, 1);
  const ClothMaterial m;
  const SeamTractionObjective t(s.garment, m);
  ASSERT_EQ(t.elements().size(), static_cast<std::size_t>(2 * (ny - 1)));
  const double stretch = 2.0 * r * std::sin(std::numbers::pi / (nx - 1)) / (w / (nx - 1));
  const double sxx = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio) * 0.5 *
                     (stretch * stretch - 1.0);
  const Points2 rest = s.garment.rest_positions();
  EXPECT_NEAR(t.value({s.x, rest}), 2.0 * h * m.thickness * sxx,
              1e-9 * 2.0 * h * m.thickness * sxx);
  for (double tr : t.tractions({s.x, rest}))
    EXPECT_NEAR(tr, m.thickness * sxx, 1e-9 * m.thickness * sxx);
}

TEST(SeamTractionObjective, GradientsOnRandomStates) {
  const test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, 0.1, 0.2, 3);
  const SeamTractionObjective t(s.garment, ClothMaterial{});
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const VecX x = test::perturb(s.x, 0.003, seed);
    const Points2 rest = test::perturb(s.garment.rest_positions(), 0.002, 30 + seed);
    const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
    EXPECT_GT(e.norm_x, 0.0);
    EXPECT_GT(e.norm_rest, 0.0);
    EXPECT_LT(e.x, 1e-6) << seed;
    EXPECT_LT(e.rest, 1e-6) << seed;
  }
}

}  // namespace tightfit::seam_traction_objective_test
