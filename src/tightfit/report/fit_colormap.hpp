#pragma once
/// Colour maps for face fields, shared by the glTF export and the report so that both
/// show the same colours for the same values.
///
/// Range rule (documented in the outputs too): a value v is mapped to
/// t = (v - lo) / (hi - lo) clamped to [0, 1]. Unless given explicitly, [lo, hi] is
/// the 1st to 99th percentile of the field's finite values (nearest rank over the
/// faces), so that one outlier does not turn the rest of the garment into one colour;
/// the data's own [min, max] is kept beside it (the report marks clamped ends and can
/// switch to it). Both are widened to include 0 when `include_zero`, so that negative
/// pressure — lift-off — is always told apart from positive; if lo == hi the range is
/// widened to lo ± max(1e-9, 1e-6 |lo|).
/// NaN values get the neutral grey kNoValueColor.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tightfit/report/fit_view.hpp"

namespace tightfit {

/// sRGB colour, components in [0, 1].
using Rgb = std::array<double, 3>;

/// Grey for faces without a value (NaN).
inline constexpr Rgb kNoValueColor = {0.6, 0.6, 0.6};

enum class ColorMap {
  kViridis,  ///< perceptually uniform, dark violet → yellow (matplotlib's viridis)
  kTurbo,    ///< rainbow-like blue → red with uniform lightness steps (Google's Turbo)
  kRegime,   ///< categorical: 0 slack, 1 wrinkled, 2 taut (values rounded, clamped)
};

/// "viridis", "turbo", "regime".
std::string colormap_name(ColorMap map);

/// Colour of a continuous map at t ∈ [0, 1] (clamped); for kRegime t is the category.
Rgb colormap_color(ColorMap map, double t);

/// One category of a categorical map.
struct ColorCategory {
  int value;
  std::string label;
  Rgb color;
};
/// The categories of kRegime: 0 slack, 1 wrinkled, 2 taut.
std::vector<ColorCategory> regime_categories();

/// How to colour faces by a scalar field.
struct FieldColoring {
  std::string field;  ///< face field name (must be a 1-component field)
  std::string label;  ///< shown in legends, e.g. "Pressure"
  std::string unit;   ///< unit of the scaled values, "" for dimensionless
  double scale =
      1.0;  ///< values are multiplied by this before mapping (Pa → mmHg: 1/kPascalPerMmHg)
  ColorMap colormap = ColorMap::kViridis;
  std::optional<double> lo;   ///< range start in scaled units; default from the data
  std::optional<double> hi;   ///< range end in scaled units; default from the data
  bool include_zero = false;  ///< widen the default range to contain 0
  /// Values below 0 get this colour instead of the map's (lift-off: negative pressure).
  std::optional<Rgb> negative_color;
};

/// The colour of lift-off (negative pressure) in the pressure colouring: magenta, a hue
/// the turbo map does not contain.
inline constexpr Rgb kLiftOffColor = {0.85, 0.1, 0.85};

/// The report's default colourings: max stretch, min stretch (viridis), pressure in
/// mmHg from pressure_pa (turbo, range includes 0, lift-off in kLiftOffColor) and regime
/// (categorical).
std::vector<FieldColoring> standard_colorings();

/// A coloring applied to one field: the scaled per-face values and the range used.
struct ResolvedColoring {
  FieldColoring coloring;
  std::vector<double> values;  ///< scaled value per face (NaN where none)
  double lo = 0.0;
  double hi = 1.0;
  /// The finite values' [min, max] (with 0 when include_zero; lo ± pad when equal).
  double data_min = 0.0;
  double data_max = 1.0;
  bool explicit_range = false;  ///< lo and hi came from the coloring, not the data

  /// Colour of a scaled value under the range rule (kNoValueColor for NaN).
  Rgb color(double value) const;
};

/// Applies `coloring` to `field` (InputError with `source` if it has more than one
/// component or an empty/inverted explicit range).
ResolvedColoring resolve_coloring(const FieldColoring& coloring, const FaceField& field,
                                  const std::string& source);

/// Converts an sRGB component in [0, 1] to linear light (glTF vertex colours are linear).
double srgb_to_linear(double c);

}  // namespace tightfit
