#pragma once
/// Fit statistics per pattern piece and for the whole garment: pressure (Pa and mmHg),
/// stretch, share of slack/wrinkled/taut area and lift-off area (negative pressure).
///
/// Areas are deformed (3D) garment face areas in m². Medians are area-weighted: the
/// value below which half of the area lies (the lower of the two middle values when
/// the half falls exactly between faces). Quantities whose field is absent, or with no
/// finite value, are NaN (written as null in JSON).
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tightfit/report/fit_view.hpp"

namespace tightfit {

/// Statistics over a set of garment faces.
struct FaceSetStatistics {
  std::string name;  ///< piece name, or "garment" for all faces
  int faces = 0;
  double area = 0.0;                ///< m²
  double pressure_min = 0.0;        ///< Pa
  double pressure_median = 0.0;     ///< Pa, area-weighted
  double pressure_max = 0.0;        ///< Pa
  double stretch_max_median = 0.0;  ///< area-weighted median of stretch_max (–)
  double stretch_max_max = 0.0;     ///< largest stretch_max (–)
  double slack_share = 0.0;         ///< share of area with regime 0, in [0, 1]
  double wrinkled_share = 0.0;      ///< share of area with regime 1
  double taut_share = 0.0;          ///< share of area with regime 2
  double liftoff_area = 0.0;        ///< m² of faces with pressure < 0
  double liftoff_share = 0.0;       ///< liftoff_area / area
};

struct FitStatistics {
  std::vector<FaceSetStatistics> pieces;  ///< one per pattern piece, in order
  FaceSetStatistics garment;              ///< all garment faces
};

/// Area-weighted median of (value, area) pairs: the value below which half of the area
/// lies, the lower of the two middle values when the half falls exactly between them;
/// non-finite values are skipped; NaN when none is left. The one median of every output
/// (report, result.json, pressure regions).
double area_weighted_median(std::vector<std::pair<double, double>> value_area);

/// Statistics of a valid view (see validate_fit_view) from its fields pressure_pa,
/// stretch_max and regime.
FitStatistics compute_fit_statistics(const FitView& view);

/// JSON form: {"garment": {...}, "pieces": [{...}]}, each with name, faces, area_m2,
/// pressure_pa {min, median, max}, pressure_mmhg {min, median, max}, stretch_max
/// {median, max}, regime_share {slack, wrinkled, taut}, liftoff_area_m2, liftoff_share.
nlohmann::json fit_statistics_json(const FitStatistics& stats);

}  // namespace tightfit
