#include "tightfit/report/fit_colormap.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tightfit/common/error.hpp"

namespace tightfit::fit_colormap_test {

void expect_rgb_near(const Rgb& got, const Rgb& want, double tol) {
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << "component " << k;
}

TEST(FitColormap, ViridisMatchesMatplotlibAtKnownPoints) {
  // matplotlib's viridis table at 0, 0.5 and 1.
  expect_rgb_near(colormap_color(ColorMap::kViridis, 0.0), {0.267004, 0.004874, 0.329415}, 0.015);
  expect_rgb_near(colormap_color(ColorMap::kViridis, 0.5), {0.127568, 0.566949, 0.550556}, 0.015);
  expect_rgb_near(colormap_color(ColorMap::kViridis, 1.0), {0.993248, 0.906157, 0.143936}, 0.015);
}

TEST(FitColormap, TurboRunsFromDarkThroughBlueToDarkRed) {
  const Rgb lo = colormap_color(ColorMap::kTurbo, 0.0);
  const Rgb blue = colormap_color(ColorMap::kTurbo, 0.15);
  const Rgb hi = colormap_color(ColorMap::kTurbo, 1.0);
  const Rgb mid = colormap_color(ColorMap::kTurbo, 0.5);
  EXPECT_LT(lo[0] + lo[1] + lo[2], 0.6);  // dark
  EXPECT_GT(blue[2], 0.8);
  EXPECT_GT(blue[2], blue[0]);
  EXPECT_GT(hi[0], 0.4);  // dark red
  EXPECT_LT(hi[1] + hi[2], 0.1);
  EXPECT_GT(mid[1], 0.8);  // bright green-yellow in the middle
  for (double t = 0.0; t <= 1.0; t += 0.05) {
    for (const double c : colormap_color(ColorMap::kTurbo, t)) {
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
    }
  }
}

TEST(FitColormap, NamesAreTheOnesScenesAndReportsUse) {
  EXPECT_EQ(colormap_name(ColorMap::kViridis), "viridis");
  EXPECT_EQ(colormap_name(ColorMap::kTurbo), "turbo");
  EXPECT_EQ(colormap_name(ColorMap::kRegime), "regime");
}

FaceField scalar(std::vector<double> v) {
  FaceField f{"f", "", MatX(static_cast<Eigen::Index>(v.size()), 1)};
  for (std::size_t i = 0; i < v.size(); ++i) f.values(static_cast<Eigen::Index>(i), 0) = v[i];
  return f;
}

TEST(FitColormap, DefaultRangeOfFewValuesIsTheirRange) {
  FieldColoring c;
  c.field = "f";
  const auto r = resolve_coloring(c, scalar({2.0, 5.0, std::nan(""), 3.0}), "x");
  EXPECT_DOUBLE_EQ(r.lo, 2.0);
  EXPECT_DOUBLE_EQ(r.hi, 5.0);
  EXPECT_TRUE(std::isnan(r.values[2]));
  expect_rgb_near(r.color(r.values[2]), kNoValueColor, 0.0);
  expect_rgb_near(r.color(2.0), colormap_color(ColorMap::kViridis, 0.0), 1e-12);
  expect_rgb_near(r.color(9.0), colormap_color(ColorMap::kViridis, 1.0), 1e-12);  // clamped
  EXPECT_DOUBLE_EQ(r.data_min, 2.0);
  EXPECT_DOUBLE_EQ(r.data_max, 5.0);
  EXPECT_FALSE(r.explicit_range);
}

TEST(FitColormap, DefaultRangeLeavesOutliers) {
  // 1000 faces stretched 1.25-1.35 and three at 1.78 (a spike): the colours span the
  // garment, not the spike; the data range is kept for the legend.
  std::vector<double> v;
  for (int i = 0; i < 1000; ++i) v.push_back(1.25 + 0.1 * i / 999.0);
  for (int i = 0; i < 3; ++i) v.push_back(1.78);
  FieldColoring c;
  c.field = "f";
  const auto r = resolve_coloring(c, scalar(v), "x");
  EXPECT_NEAR(r.lo, 1.251, 1e-3);  // the 1st percentile
  EXPECT_NEAR(r.hi, 1.349, 1e-3);  // the 99th
  EXPECT_DOUBLE_EQ(r.data_min, 1.25);
  EXPECT_DOUBLE_EQ(r.data_max, 1.78);
  // include_zero widens both ranges.
  c.include_zero = true;
  const auto z = resolve_coloring(c, scalar(v), "x");
  EXPECT_EQ(z.lo, 0.0);
  EXPECT_EQ(z.data_min, 0.0);
  EXPECT_NEAR(z.hi, 1.349, 1e-3);
}

TEST(FitColormap, ScaleIncludeZeroAndExplicitRange) {
  FieldColoring c;
  c.field = "f";
  c.scale = 0.5;
  c.include_zero = true;
  auto r = resolve_coloring(c, scalar({4.0, 8.0}), "x");
  EXPECT_DOUBLE_EQ(r.values[1], 4.0);
  EXPECT_DOUBLE_EQ(r.lo, 0.0);
  EXPECT_DOUBLE_EQ(r.hi, 4.0);
  c.lo = -1.0;
  c.hi = 1.0;
  r = resolve_coloring(c, scalar({4.0, 8.0}), "x");
  EXPECT_DOUBLE_EQ(r.lo, -1.0);
  EXPECT_DOUBLE_EQ(r.hi, 1.0);
  c.lo = 2.0;
  EXPECT_THROW(resolve_coloring(c, scalar({4.0}), "x"), InputError);
}

TEST(FitColormap, ConstantFieldGetsAWidenedRange) {
  FieldColoring c;
  c.field = "f";
  const auto r = resolve_coloring(c, scalar({3.0, 3.0}), "x");
  EXPECT_LT(r.lo, 3.0);
  EXPECT_GT(r.hi, 3.0);
}

TEST(FitColormap, RegimeIsCategorical) {
  const auto cats = regime_categories();
  ASSERT_EQ(cats.size(), 3u);
  EXPECT_EQ(cats[0].label, "slack");
  EXPECT_EQ(cats[2].label, "taut");
  expect_rgb_near(colormap_color(ColorMap::kRegime, 1.2), cats[1].color, 0.0);
  expect_rgb_near(colormap_color(ColorMap::kRegime, 7.0), cats[2].color, 0.0);
}

TEST(FitColormap, RejectsVectorFields) {
  FaceField dir{"stretch_dir", "", MatX::Zero(2, 3)};
  FieldColoring c;
  c.field = "stretch_dir";
  EXPECT_THROW(resolve_coloring(c, dir, "x"), InputError);
}

TEST(FitColormap, StandardColorings) {
  const auto list = standard_colorings();
  ASSERT_EQ(list.size(), 4u);
  EXPECT_EQ(list[0].field, "stretch_max");
  EXPECT_EQ(list[1].field, "stretch_min");
  EXPECT_EQ(list[2].field, "pressure_pa");
  EXPECT_EQ(list[2].unit, "mmHg");
  EXPECT_NEAR(list[2].scale * kPascalPerMmHg, 1.0, 1e-15);
  EXPECT_TRUE(list[2].include_zero);
  EXPECT_EQ(list[3].colormap, ColorMap::kRegime);
  // Lift-off (negative pressure) has its own colour; zero and above follow the map.
  ASSERT_TRUE(list[2].negative_color.has_value());
  const auto r = resolve_coloring(list[2], scalar({-100.0, 0.0, 4000.0}), "x");
  expect_rgb_near(r.color(r.values[0]), kLiftOffColor, 0.0);
  expect_rgb_near(r.color(r.values[1]),
                  colormap_color(ColorMap::kTurbo, (0.0 - r.lo) / (r.hi - r.lo)), 1e-12);
  EXPECT_FALSE(list[0].negative_color.has_value());
}

TEST(FitColormap, SrgbToLinear) {
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-12);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.214041, 1e-6);
}

}  // namespace tightfit::fit_colormap_test
