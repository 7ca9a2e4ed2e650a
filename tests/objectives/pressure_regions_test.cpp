#include "tightfit/objectives/pressure_regions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/objectives/pressure_objective.hpp"

namespace tightfit {
namespace {

constexpr double kBandSleeveRadius = 0.05;

/// A sleeve 10 cm long on a cylinder of radius 5 cm along z (one piece, "grid").
test::GarmentState region_sleeve(int nx = 17, int ny = 9) {
  return test::sleeve(nx, ny, kBandSleeveRadius, 0.9 * 2.0 * std::numbers::pi * kBandSleeveRadius, 0.1, 0.2, 3);
}

/// The band between heights `lo` and `hi` (m) along z.
PressureRegion band(const std::string& name, double lo, double hi, double transition,
                    double min_pa, double max_pa) {
  PressureRegion r;
  r.name = name;
  r.above = RegionPlane{Vec3(0, 0, lo), Vec3(0, 0, 2)};  // normals need not be unit
  r.below = RegionPlane{Vec3(0, 0, hi), Vec3(0, 0, 1)};
  r.transition = transition;
  r.min_pa = min_pa;
  r.max_pa = max_pa;
  return r;
}

double centroid_height(const test::GarmentState& s, Eigen::Index e) {
  double z = 0.0;
  for (int k = 0; k < 3; ++k) z += s.x[3 * s.garment.garment_triangles(e, k) + 2] / 3.0;
  return z;
}

TEST(PressureRegions, BandWeightsAreSmoothStepsAcrossThePlanes) {
  const test::GarmentState s = region_sleeve();
  const PressureRegions hard(s.garment, {band("b", 0.03, 0.07, 0.0, 0, 1)}, "test");
  const PressureRegions soft(s.garment, {band("b", 0.03, 0.07, 0.02, 0, 1)}, "test");
  const MatX wh = hard.weights(s.x), ws = soft.weights(s.x);
  for (Eigen::Index e = 0; e < wh.cols(); ++e) {
    const double z = centroid_height(s, e);
    EXPECT_EQ(wh(0, e), z >= 0.03 && z <= 0.07 ? 1.0 : 0.0) << z;
    const auto step = [](double t) {
      const double u = std::clamp(t + 0.5, 0.0, 1.0);
      return u * u * (3 - 2 * u);
    };
    EXPECT_NEAR(ws(0, e), step((z - 0.03) / 0.02) * step((0.07 - z) / 0.02), 1e-14) << z;
  }
  EXPECT_GT(ws.maxCoeff(), 0.999);
  EXPECT_GT((ws.array() > 0.01 && ws.array() < 0.99).count(), 0);  // some in transition
}

TEST(PressureRegions, HardBandValueEqualsThePerElementRange) {
  const test::GarmentState s = region_sleeve();
  const Points2 rest = s.garment.rest_positions();
  const PressureObjective probe(s.garment, ClothMaterial{}, 0.0, 1e9);
  const double mean = probe.pressures({s.x, rest}).mean();
  const double lo = 1.2 * mean, hi = 2.0 * mean;
  const PressureObjective by_region(
      s.garment, ClothMaterial{},
      PressureRegions(s.garment, {band("b", 0.03, 0.07, 0.0, lo, hi)}, "test"));
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::Index m = s.garment.garment_triangles.rows();
  VecX min_p = VecX::Constant(m, -inf), max_p = VecX::Constant(m, inf);
  int inside = 0;
  for (Eigen::Index e = 0; e < m; ++e) {
    const double z = centroid_height(s, e);
    if (z < 0.03 || z > 0.07) continue;
    min_p[e] = lo;
    max_p[e] = hi;
    ++inside;
  }
  ASSERT_GT(inside, 0);
  ASSERT_LT(inside, m);
  const PressureObjective by_element(s.garment, ClothMaterial{}, min_p, max_p);
  const double expected = by_element.value({s.x, rest});
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(by_region.value({s.x, rest}), expected, 1e-12 * expected);
  // Two overlapping regions sum: the whole piece plus the band.
  PressureRegion whole;
  whole.name = "whole";
  whole.pieces = {"grid"};
  whole.min_pa = lo;
  whole.max_pa = hi;
  const PressureObjective both(
      s.garment, ClothMaterial{},
      PressureRegions(s.garment, {band("b", 0.03, 0.07, 0.0, lo, hi), whole}, "test"));
  const PressureObjective everywhere(s.garment, ClothMaterial{}, lo, hi);
  EXPECT_NEAR(both.value({s.x, rest}), expected + everywhere.value({s.x, rest}),
              1e-12 * (expected + everywhere.value({s.x, rest})));
}

TEST(PressureRegions, GradientWithSmoothBandsMatchesFiniteDifferences) {
  const test::GarmentState s = region_sleeve(9, 7);
  const Points2 rest0 = s.garment.rest_positions();
  const PressureObjective probe(s.garment, ClothMaterial{}, 0.0, 1e9);
  const double mean = probe.pressures({s.x, rest0}).mean();
  PressureRegion whole;
  whole.name = "whole";
  whole.pieces = {"grid"};
  whole.min_pa = 0.9 * mean;
  whole.max_pa = 1.1 * mean;
  // Bands with transitions wider than an element, so that triangles sit on the slopes.
  const PressureObjective t(
      s.garment, ClothMaterial{},
      PressureRegions(s.garment,
                      {band("low", 0.0, 0.04, 0.03, 2.0 * mean, 3.0 * mean),
                       band("high", 0.05, 0.1, 0.03, 0.2 * mean, 0.5 * mean), whole},
                      "test"));
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const VecX x = test::perturb(s.x, 0.002, seed);
    const Points2 rest = test::perturb(rest0, 0.001, 30 + seed);
    const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
    EXPECT_GT(e.norm_x, 0.0);
    EXPECT_LT(e.x, 1e-6) << "seed " << seed;
    EXPECT_LT(e.rest, 1e-6) << "seed " << seed;
  }
}

TEST(PressureRegions, BadRegionsAreInputErrorsNamingThem) {
  const test::GarmentState s = region_sleeve();
  auto message = [&](std::vector<PressureRegion> regions) -> std::string {
    try {
      const PressureRegions r(s.garment, std::move(regions), "scene.json");
      r.check_covered(s.x, "scene.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  PressureRegion thigh = band("thigh", 0.03, 0.07, 0.0, 1, 2);
  thigh.pieces = {"front"};
  EXPECT_NE(message({thigh}).find("no piece \"front\""), std::string::npos) << message({thigh});
  EXPECT_NE(message({thigh}).find("\"thigh\""), std::string::npos);
  EXPECT_NE(message({band("above head", 1.0, 2.0, 0.0, 1, 2)}).find("\"above head\""),
            std::string::npos);
  EXPECT_NE(message({band("a", 0.0, 0.1, 0.0, 1, 2), band("a", 0.0, 0.1, 0.0, 1, 2)})
                .find("two pressure regions"),
            std::string::npos);
  EXPECT_NE(message({band("inverted", 0.0, 0.1, 0.0, 2, 1)}).find("min <= max"), std::string::npos);
  PressureRegion flat = band("flat", 0.0, 0.1, 0.0, 1, 2);
  flat.above->normal.setZero();
  EXPECT_NE(message({flat}).find("non-zero normal"), std::string::npos);
  EXPECT_EQ(message({band("ok", 0.0, 0.1, 0.005, 1, 2)}), "");
}

}  // namespace
}  // namespace tightfit
