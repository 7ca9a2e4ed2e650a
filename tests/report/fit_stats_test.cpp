#include "tightfit/report/fit_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "report/support/fit_test_view.hpp"

namespace tightfit::fit_stats_test {

/// Four right triangles of areas 1, 1, 2, 4 (m²) in one piece "a" (faces 0, 1) and
/// one piece "b" (faces 2, 3).
FitView four_triangles(std::vector<double> pressure, std::vector<double> regime) {
  FitView v;
  v.garment.vertices.resize(12, 3);
  v.garment.faces.resize(4, 3);
  const double legs[4] = {std::sqrt(2.0), std::sqrt(2.0), 2.0, std::sqrt(8.0)};
  for (int f = 0; f < 4; ++f) {
    const double x = 10.0 * f;
    v.garment.vertices.row(3 * f) << x, 0, 0;
    v.garment.vertices.row(3 * f + 1) << x + legs[f], 0, 0;
    v.garment.vertices.row(3 * f + 2) << x, legs[f], 0;
    v.garment.faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
  for (const char* name : {"a", "b"}) {
    PatternPiece p;
    p.name = name;
    p.rest.resize(4, 2);
    p.rest << 0, 0, 1, 0, 1, 1, 0, 1;
    p.triangles.resize(2, 3);
    p.triangles << 0, 1, 2, 0, 2, 3;
    v.pattern.pieces.push_back(p);
  }
  FaceField p{"pressure_pa", "Pa", MatX(4, 1)};
  FaceField r{"regime", "", MatX(4, 1)};
  for (int f = 0; f < 4; ++f) {
    p.values(f, 0) = pressure[static_cast<std::size_t>(f)];
    r.values(f, 0) = regime[static_cast<std::size_t>(f)];
  }
  v.garment_fields = {p, r};
  return v;
}

TEST(FitStats, PerPieceAndTotals) {
  const FitView v = four_triangles({-100.0, 300.0, 200.0, 1000.0}, {0, 1, 2, 2});
  const FitStatistics s = compute_fit_statistics(v);
  ASSERT_EQ(s.pieces.size(), 2u);
  const auto& a = s.pieces[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.faces, 2);
  EXPECT_NEAR(a.area, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.pressure_min, -100.0);
  EXPECT_DOUBLE_EQ(a.pressure_max, 300.0);
  EXPECT_DOUBLE_EQ(a.pressure_median, -100.0);  // half the area at or below -100
  EXPECT_NEAR(a.liftoff_area, 1.0, 1e-12);
  EXPECT_NEAR(a.liftoff_share, 0.5, 1e-12);
  EXPECT_NEAR(a.slack_share, 0.5, 1e-12);
  EXPECT_NEAR(a.wrinkled_share, 0.5, 1e-12);
  EXPECT_NEAR(a.taut_share, 0.0, 1e-12);

  const auto& g = s.garment;
  EXPECT_NEAR(g.area, 8.0, 1e-12);
  // Sorted by pressure: -100 (area 1), 200 (2), 300 (1), 1000 (4): the cumulative area
  // reaches half of 8 at 300.
  EXPECT_DOUBLE_EQ(g.pressure_median, 300.0);
  EXPECT_NEAR(g.liftoff_share, 1.0 / 8.0, 1e-12);
  EXPECT_NEAR(g.taut_share, 6.0 / 8.0, 1e-12);
  EXPECT_TRUE(std::isnan(g.stretch_max_median));  // no stretch field
}

TEST(FitStats, JsonHasBothPressureUnitsAndLiftOffEvenWhenZero) {
  const FitView v = four_triangles({100.0, 300.0, 200.0, 1000.0}, {2, 2, 2, 2});
  const auto j = fit_statistics_json(compute_fit_statistics(v));
  EXPECT_DOUBLE_EQ(j["garment"]["pressure_pa"]["max"].get<double>(), 1000.0);
  EXPECT_NEAR(j["garment"]["pressure_mmhg"]["max"].get<double>(), 1000.0 / kPascalPerMmHg, 1e-12);
  EXPECT_DOUBLE_EQ(j["garment"]["liftoff_area_m2"].get<double>(), 0.0);
  EXPECT_TRUE(j["garment"]["stretch_max"]["median"].is_null());
  EXPECT_EQ(j["pieces"].size(), 2u);
  EXPECT_EQ(j["pieces"][1]["name"], "b");
}

TEST(FitStats, BandOnSphereLiftOffMatchesTheSyntheticField) {
  const FitView v = test::band_on_sphere(48, 4);
  const FitStatistics s = compute_fit_statistics(v);
  // Pressure 400 + 2400 sin(theta) < 0 where sin(theta) < -1/6: a share of
  // 1 - acos(-1/6)/pi of the band (faces sampled at centroids).
  const double expected = 1.0 - std::acos(-1.0 / 6.0) / std::numbers::pi;
  EXPECT_NEAR(s.garment.liftoff_share, expected, 0.03);
  EXPECT_NEAR(s.garment.pressure_max, 2800.0, 10.0);
  EXPECT_NEAR(s.garment.pressure_min, -2000.0, 10.0);
  // Centroids nearest the middle are a third of a row (0.02 m) away: 1.05 + 0.3 (1 - 1/6).
  EXPECT_NEAR(s.garment.stretch_max_max, 1.3, 1e-12);
  EXPECT_NEAR(s.garment.slack_share + s.garment.wrinkled_share + s.garment.taut_share, 1.0, 1e-12);
  // The front piece (theta in 0..pi) lifts off less than the back piece.
  EXPECT_LT(s.pieces[0].liftoff_share, s.pieces[1].liftoff_share);
}

}  // namespace tightfit::fit_stats_test
