#include "tightfit/report/fit_colormap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"

namespace tightfit {

namespace {

double clamp01(double t) { return std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0; }

/// Polynomial fit of matplotlib's viridis (degree 6, minimax; coefficients published
/// by Matt Zucker under CC0, fitted to the BIDS colormap data, also CC0).
Rgb viridis(double t) {
  static constexpr double kCoefficients[7][3] = {
      {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
      {0.1050930431085774, 1.404613529898575, 1.384590162594685},
      {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
      {-4.634230498983486, -5.799100973351585, -19.33244095627987},
      {6.228269936347081, 14.17993336680509, 56.69055260068105},
      {4.776384997670288, -13.74514537774601, -65.35303263337234},
      {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  Rgb rgb{};
  for (int k = 0; k < 3; ++k) {
    double v = kCoefficients[6][k];
    for (int i = 5; i >= 0; --i) v = v * t + kCoefficients[i][k];
    rgb[static_cast<std::size_t>(k)] = std::clamp(v, 0.0, 1.0);
  }
  return rgb;
}

/// Polynomial approximation of Google's Turbo (degree 5; Copyright 2019 Google LLC,
/// Apache-2.0, by Anton Mikhailov and Ruofei Du).
Rgb turbo(double t) {
  static constexpr double kCoefficients[6][3] = {
      {0.13572138, 0.09140261, 0.10667330},      {4.61539260, 2.19418839, 12.64194608},
      {-42.66032258, 4.84296658, -60.58204836},  {132.13108234, -14.18503333, 110.36276771},
      {-152.94239396, 4.27729857, -89.90310912}, {59.28637943, 2.82956604, 27.34824973}};
  Rgb rgb{};
  for (int k = 0; k < 3; ++k) {
    double v = kCoefficients[5][k];
    for (int i = 4; i >= 0; --i) v = v * t + kCoefficients[i][k];
    rgb[static_cast<std::size_t>(k)] = std::clamp(v, 0.0, 1.0);
  }
  return rgb;
}

Rgb hex(unsigned value) {
  return {((value >> 16) & 0xFFu) / 255.0, ((value >> 8) & 0xFFu) / 255.0, (value & 0xFFu) / 255.0};
}

}  // namespace

std::string colormap_name(ColorMap map) {
  switch (map) {
    case ColorMap::kViridis:
      return "viridis";
    case ColorMap::kTurbo:
      return "turbo";
    case ColorMap::kRegime:
      return "regime";
  }
  return "viridis";
}

std::vector<ColorCategory> regime_categories() {
  return {{static_cast<int>(ClothRegime::kSlack), regime_name(ClothRegime::kSlack), hex(0x9ecae1)},
          {static_cast<int>(ClothRegime::kWrinkled), regime_name(ClothRegime::kWrinkled),
           hex(0xf28e2b)},
          {static_cast<int>(ClothRegime::kTaut), regime_name(ClothRegime::kTaut), hex(0x2a7f62)}};
}

Rgb colormap_color(ColorMap map, double t) {
  switch (map) {
    case ColorMap::kViridis:
      return viridis(clamp01(t));
    case ColorMap::kTurbo:
      return turbo(clamp01(t));
    case ColorMap::kRegime: {
      const auto categories = regime_categories();
      const double r = std::isfinite(t) ? std::round(t) : 0.0;
      const auto i = static_cast<std::size_t>(std::clamp(r, 0.0, 2.0));
      return categories[i].color;
    }
  }
  return kNoValueColor;
}

std::vector<FieldColoring> standard_colorings() {
  std::vector<FieldColoring> list;
  list.push_back({std::string(fit_fields::kStretchMax), "Max principal stretch", "", 1.0,
                  ColorMap::kViridis, std::nullopt, std::nullopt, false, std::nullopt});
  list.push_back({std::string(fit_fields::kStretchMin), "Min principal stretch", "", 1.0,
                  ColorMap::kViridis, std::nullopt, std::nullopt, false, std::nullopt});
  list.push_back({std::string(fit_fields::kPressurePa), "Pressure", "mmHg", 1.0 / kPascalPerMmHg,
                  ColorMap::kTurbo, std::nullopt, std::nullopt, true, kLiftOffColor});
  list.push_back({std::string(fit_fields::kRegime), "Regime", "", 1.0, ColorMap::kRegime, 0.0, 2.0,
                  false, std::nullopt});
  return list;
}

Rgb ResolvedColoring::color(double value) const {
  if (std::isnan(value)) return kNoValueColor;
  if (coloring.colormap == ColorMap::kRegime) return colormap_color(ColorMap::kRegime, value);
  if (coloring.negative_color && value < 0.0) return *coloring.negative_color;
  return colormap_color(coloring.colormap, (value - lo) / (hi - lo));
}

ResolvedColoring resolve_coloring(const FieldColoring& coloring, const FaceField& field,
                                  const std::string& source) {
  if (field.components() != 1) {
    throw InputError(source, "cannot colour by field '" + field.name + "': it has " +
                                 std::to_string(field.components()) + " components, not 1");
  }
  ResolvedColoring out;
  out.coloring = coloring;
  out.values.resize(static_cast<std::size_t>(field.values.rows()));
  std::vector<double> finite;
  for (Eigen::Index i = 0; i < field.values.rows(); ++i) {
    const double v = field.values(i, 0) * coloring.scale;
    out.values[static_cast<std::size_t>(i)] = std::isfinite(v) ? v : std::nan("");
    if (std::isfinite(v)) finite.push_back(v);
  }
  double lo = 0.0, hi = 1.0, data_min = 0.0, data_max = 1.0;
  if (!finite.empty()) {
    std::sort(finite.begin(), finite.end());
    const auto last = static_cast<double>(finite.size() - 1);
    lo = finite[static_cast<size_t>(std::floor(0.01 * last))];
    hi = finite[static_cast<size_t>(std::ceil(0.99 * last))];
    data_min = finite.front();
    data_max = finite.back();
  }
  if (coloring.include_zero) {
    lo = std::min(lo, 0.0);
    hi = std::max(hi, 0.0);
    data_min = std::min(data_min, 0.0);
    data_max = std::max(data_max, 0.0);
  }
  if (coloring.lo) lo = *coloring.lo;
  if (coloring.hi) hi = *coloring.hi;
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    throw InputError(source, "colour range for '" + field.name + "' must be finite with lo <= hi");
  }
  auto widen = [](double& a, double& b) {
    if (a != b) return;
    const double pad = std::max(1e-9, 1e-6 * std::abs(a));
    a -= pad;
    b += pad;
  };
  widen(lo, hi);
  widen(data_min, data_max);
  out.lo = lo;
  out.hi = hi;
  out.data_min = data_min;
  out.data_max = data_max;
  out.explicit_range = coloring.lo.has_value() || coloring.hi.has_value();
  return out;
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace tightfit
