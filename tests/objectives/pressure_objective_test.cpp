#include "tightfit/objectives/pressure_objective.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/physics/cloth_analysis.hpp"
#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"

namespace tightfit::pressure_objective_test {

constexpr double kRadius = 0.05;

/// A sleeve on a cylinder of radius 5 cm, rest circumference 90 % of the deformed one.
test::GarmentState test_sleeve(double jitter, int nx = 17, int ny = 6) {
  return test::sleeve(nx, ny, kRadius, 0.9 * 2.0 * std::numbers::pi * kRadius, 0.1, jitter, 7);
}

Points3 as_points(const VecX& x) { return Eigen::Map<const Points3>(x.data(), x.size() / 3, 3); }

TEST(PressureObjective, ShapeOperatorsAgreeWithThePhysicsLayer) {
  const test::GarmentState s = test_sleeve(0.2);
  const VecX x = test::perturb(s.x, 0.002, 1);
  const PressureObjective t(s.garment, ClothMaterial{}, 0.0, 1e3);
  const std::vector<Mat3> ours = t.shape_operators(x);
  MidEdgeShapeOperator reference(s.garment.topology->garment_triangles,
                                 s.garment.num_garment_vertices());
  const std::vector<Mat3> theirs = reference.compute(as_points(x));
  ASSERT_EQ(ours.size(), theirs.size());
  double scale = 0.0, diff = 0.0;
  for (std::size_t f = 0; f < ours.size(); ++f) {
    scale = std::max(scale, theirs[f].norm());
    diff = std::max(diff, (ours[f] - theirs[f]).norm());
  }
  EXPECT_GT(scale, 10.0);  // ~1/R = 20 per metre
  EXPECT_LT(diff, 1e-10 * scale);
}

TEST(PressureObjective, PressuresAgreeWithYoungLaplaceAnalysis) {
  const test::GarmentState s = test_sleeve(0.2);
  const VecX x = test::perturb(s.x, 0.002, 2);
  const Points2 rest = s.garment.rest_positions();
  const ClothMaterial material;
  const PressureObjective t(s.garment, material, 0.0, 1e3);
  const VecX ours = t.pressures({x, rest});
  const ClothEnergy cloth(s.garment.topology->pattern_triangles, rest,
                          s.garment.topology->pattern_to_garment, s.garment.num_garment_vertices(),
                          material);
  const VecX theirs = young_laplace_pressure(
      analyze_cloth(cloth, x),
      mid_edge_shape_operators(as_points(x), s.garment.topology->garment_triangles));
  ASSERT_EQ(ours.size(), theirs.size());
  EXPECT_LT((ours - theirs).cwiseAbs().maxCoeff(), 1e-9 * theirs.cwiseAbs().maxCoeff());
}

TEST(PressureObjective, UniformSleeveMatchesHoopTensionOverRadius) {
  // Regular sleeve, hoop stretch ≈ 1/0.9, no axial stretch: p = T_hoop / R.
  const test::GarmentState s = test_sleeve(0.0, 65, 6);
  const Points2 rest = s.garment.rest_positions();
  const ClothMaterial material;
  const PressureObjective t(s.garment, material, 0.0, 1e3);
  const VecX p = t.pressures({s.x, rest});
  const ClothEnergy cloth(s.garment.topology->pattern_triangles, rest,
                          s.garment.topology->pattern_to_garment, s.garment.num_garment_vertices(),
                          material);
  const std::vector<ClothElementFit> fit = analyze_cloth(cloth, s.x);
  for (Eigen::Index e = 0; e < p.size(); ++e) {
    const double hoop = fit[e].principal_tension[0];
    EXPECT_GT(p[e], 0.0);
    EXPECT_NEAR(p[e], hoop / kRadius, 0.01 * hoop / kRadius) << e;
  }
}

TEST(PressureObjective, ValueByHandAndRange) {
  const test::GarmentState s = test_sleeve(0.2);
  const Points2 rest = s.garment.rest_positions();
  const PressureObjective probe(s.garment, ClothMaterial{}, 0.0, 1e9);
  const VecX p = probe.pressures({s.x, rest});
  EXPECT_EQ(probe.value({s.x, rest}), 0.0);
  const double lo = p.maxCoeff() * 1.2;  // every element below the range
  const PressureObjective t(s.garment, ClothMaterial{}, lo, 2.0 * lo);
  double expected = 0.0;
  for (Eigen::Index e = 0; e < p.size(); ++e) {
    const auto tri = s.garment.topology->pattern_triangles.row(e);
    const Vec2 e1 = (rest.row(tri[1]) - rest.row(tri[0])).transpose();
    const Vec2 e2 = (rest.row(tri[2]) - rest.row(tri[0])).transpose();
    const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    ASSERT_LT(p[e], lo);
    expected += area * (p[e] - lo) * (p[e] - lo);
  }
  EXPECT_NEAR(t.value({s.x, rest}), expected, 1e-12 * expected);
  EXPECT_THROW(PressureObjective(s.garment, ClothMaterial{}, 2.0, 1.0), InputError);
  EXPECT_THROW(PressureObjective(s.garment, ClothMaterial{}, VecX::Zero(3), VecX::Ones(3)),
               InputError);
}

TEST(PressureObjective, GradientIncludingTheEdgeUnknownsMatchesFiniteDifferences) {
  const test::GarmentState s = test_sleeve(0.2, 9, 5);
  const Points2 rest0 = s.garment.rest_positions();
  const PressureObjective probe(s.garment, ClothMaterial{}, 0.0, 1e9);
  const double mean = probe.pressures({s.x, rest0}).mean();
  // Partly active range (some elements above, some below, some inside) and fully active.
  for (const auto& [lo, hi] :
       {std::pair{0.9 * mean, 1.1 * mean}, std::pair{2.0 * mean, 3.0 * mean}}) {
    const PressureObjective t(s.garment, ClothMaterial{}, lo, hi);
    for (unsigned seed = 1; seed <= 2; ++seed) {
      const VecX x = test::perturb(s.x, 0.002, seed);
      const Points2 rest = test::perturb(rest0, 0.001, 20 + seed);
      const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
      EXPECT_GT(e.norm_x, 0.0);
      EXPECT_LT(e.x, 1e-6) << lo << " seed " << seed;
      EXPECT_LT(e.rest, 1e-6) << lo << " seed " << seed;
    }
  }
}

}  // namespace tightfit::pressure_objective_test
