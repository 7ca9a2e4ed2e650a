#include "tightfit/objectives/pressure_regions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/objectives/pressure_objective.hpp"

namespace tightfit::pressure_regions_test {

constexpr double kBandSleeveRadius = 0.05;

/// A sleeve 10 cm long on a cylinder of radius 5 cm along z (one piece, "grid").
test::GarmentState region_sleeve(int nx = 17, int ny = 9) {
  return test::sleeve(nx, ny, kBandSleeveRadius, 0.9 * 2.0 * std::numbers::pi * kBandSleeveRadius,
                      0.1, 0.2, 3);
}

/// The band between heights `lo` and `hi` (m) along z.
PressureRegion band(const std::string& name, double lo, double hi, double transition, double min_pa,
                    double max_pa) {
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
  for (int k = 0; k < 3; ++k) z += s.x[3 * s.garment.topology->garment_triangles(e, k) + 2] / 3.0;
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
  const Eigen::Index m = s.garment.topology->garment_triangles.rows();
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

}  // namespace tightfit::pressure_regions_test

namespace tightfit::pressure_regions_test {

TEST(PointField, ConstantsExactlyValuesInRangeGradientByFiniteDifferences) {
  Points3 p(200, 3);
  VecX v(200), ones = VecX::Ones(200);
  for (int k = 0; k < 200; ++k) {
    p.row(k) << 0.01 * (k % 10), 0.01 * ((k / 10) % 10), 0.01 * (k / 100);
    v[k] = std::sin(30.0 * p(k, 0)) * std::cos(20.0 * p(k, 1));
  }
  const PointField constant(p, ones, 0.025), field(p, v, 0.025);
  const Vec3 x(0.043, 0.051, 0.004);
  EXPECT_NEAR(constant.evaluate(x).value, 1.0, 1e-14);
  EXPECT_NEAR(constant.evaluate(x).gradient.norm(), 0.0, 1e-10);
  const PointField::Evaluation e = field.evaluate(x);
  EXPECT_GE(e.value, v.minCoeff());
  EXPECT_LE(e.value, v.maxCoeff());
  for (int d = 0; d < 3; ++d) {
    const double h = 1e-6;
    Vec3 a = x, b = x;
    a[d] += h;
    b[d] -= h;
    const double fd = (field.evaluate(a).value - field.evaluate(b).value) / (2 * h);
    EXPECT_NEAR(e.gradient[d], fd, 1e-6 * (1.0 + std::abs(fd))) << d;
  }
  // Far from every point: the nearest point's value, gradient 0.
  const PointField::Evaluation far = field.evaluate(Vec3(1, 1, 1));
  EXPECT_EQ(far.value, v[199]);
  EXPECT_EQ(far.gradient.norm(), 0.0);
}

/// A rig for the test sleeve: points on the cylinder, bone "top" weighs 1 above z = 0.05
/// and 0 below, bone "bottom" the opposite.
SkinWeights sleeve_rig() {
  SkinWeights rig;
  rig.source = "test rig";
  const int n_theta = 48, n_z = 25;
  rig.vertices.resize(n_theta * n_z, 3);
  for (int j = 0; j < n_z; ++j)
    for (int i = 0; i < n_theta; ++i) {
      const int v = j * n_theta + i;
      const double a = 2 * std::numbers::pi * i / n_theta, z = -0.01 + 0.005 * j;
      rig.vertices.row(v) << kBandSleeveRadius * std::cos(a), kBandSleeveRadius * std::sin(a), z;
      rig.bones[z > 0.05 ? "top" : "bottom"].emplace_back(v, 1.0);
    }
  return rig;
}

TEST(PressureRegions, BoneRegionsFollowTheSkinWeightsAndTheirGradientIsExact) {
  const test::GarmentState s = region_sleeve(9, 7);
  const SkinWeights rig = sleeve_rig();
  PressureRegion top;
  top.name = "top";
  top.bones = {"top"};
  const PressureRegions regions(s.garment, {top}, "test", &rig, 0.012);
  const MatX w = regions.weights(s.x);
  for (Eigen::Index e = 0; e < w.cols(); ++e) {
    const double z = centroid_height(s, e);
    if (z > 0.065) {
      EXPECT_NEAR(w(0, e), 1.0, 1e-12) << z;
    }
    if (z < 0.035) {
      EXPECT_NEAR(w(0, e), 0.0, 1e-12) << z;
    }
  }
  const Points2 rest0 = s.garment.rest_positions();
  const PressureObjective probe(s.garment, ClothMaterial{}, 0.0, 1e9);
  const double mean = probe.pressures({s.x, rest0}).mean();
  top.min_pa = 2.0 * mean;
  top.max_pa = 3.0 * mean;
  PressureRegion bottom = top;
  bottom.name = "bottom";
  bottom.bones = {"bottom"};
  bottom.min_pa = 0.1 * mean;
  bottom.max_pa = 0.2 * mean;
  const PressureObjective t(s.garment, ClothMaterial{},
                            PressureRegions(s.garment, {top, bottom}, "test", &rig, 0.012));
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const VecX x = test::perturb(s.x, 0.002, seed);
    const Points2 rest = test::perturb(rest0, 0.001, 40 + seed);
    const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
    EXPECT_GT(e.norm_x, 0.0);
    EXPECT_LT(e.x, 1e-6) << "seed " << seed;
    EXPECT_LT(e.rest, 1e-6) << "seed " << seed;
  }
  // Bones without a rig, or a bone the rig lacks: input errors naming the region.
  EXPECT_THROW(PressureRegions(s.garment, {top}, "test"), InputError);
  PressureRegion tail = top;
  tail.bones = {"tail"};
  try {
    PressureRegions(s.garment, {tail}, "test", &rig, 0.012);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"tail\""), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::pressure_regions_test
