#pragma once
/// Pressure of a compression garment against its targets and the medical classes: per
/// pressure region (design/pressure_region.hpp) the area-weighted pressure statistics,
/// the share of the region's area inside its target range, the lift-off share and the
/// compression class its median reaches.
///
/// Classes (docs/design.md §5, public sources): RAL-GZ 387 (the German/Austrian/Swiss
/// quality mark for medical compression stockings, pressure at the ankle): class I
/// 18–21, II 23–32, III 34–46, IV >= 49 mmHg; burn-scar pressure therapy 15–25 mmHg
/// (meta-analysis of 12 trials); face masks 20–32 mmHg. UK (BS 661210) and French
/// (ASQUAL) stocking classes differ and are not used here.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/body/skin_weights.hpp"
#include "tightfit/objectives/pressure_region.hpp"
#include "tightfit/report/fit_view.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

/// The RAL-GZ 387 class of a pressure (mmHg): "I", "II", "III", "IV", or where it falls
/// outside the classes "below I", "between I and II", "between II and III",
/// "between III and IV". Boundaries are inclusive (18 and 21 are class I).
std::string ral_gz_387_class(double mmhg);

/// Whether a pressure (mmHg) lies in the burn-scar therapy range 15–25 and in the face
/// mask range 20–32 (inclusive).
bool in_burn_scar_range(double mmhg);
bool in_face_mask_range(double mmhg);

/// Area-weighted mean and standard deviation (Pa) of per-element pressures `p` over the
/// elements `faces` with deformed areas `areas` (m²).
struct PressureMoments {
  double mean = 0.0;  ///< Pa
  double std = 0.0;   ///< Pa
  double area = 0.0;  ///< m²
};
PressureMoments pressure_moments(const VecX& p, const std::vector<double>& areas,
                                 const std::vector<int>& faces);

/// An area-weighted pressure histogram: bins of a "nice" width (1, 2 or 5 × 10^k mmHg,
/// about `target_bins` of them) from below the smallest to above the largest value,
/// with a bin edge at 0 so that lift-off (p < 0) has bins of its own.
struct PressureHistogram {
  std::vector<double> edges_mmhg;  ///< bins + 1 ascending edges
  std::vector<double> area_m2;     ///< area per bin
};
PressureHistogram pressure_histogram(const VecX& p, const std::vector<double>& areas,
                                     const std::vector<int>& faces, int target_bins = 24);

/// A scene's pressure regions with the rig their bone regions need (may be null).
struct PressureRegionSet {
  std::vector<PressureRegion> regions;
  const SkinWeights* rig = nullptr;
  double rig_radius = 0.03;  ///< m
  bool empty() const { return regions.empty(); }
};

/// Pressure above which the outputs warn (mmHg): beyond the compression classes used for
/// day-long wear (RAL-GZ 387 III tops at 46; 40 mmHg is the usual alarm for skin and
/// circulation under a garment worn all day).
inline constexpr double kPressureWarningMmHg = 40.0;

/// Share of the area of `faces` whose pressure exceeds kPressureWarningMmHg.
double share_above_warning(const VecX& p, const std::vector<double>& areas,
                           const std::vector<int>& faces);

/// The faces of each region at the simulation's equilibrium (membership weight >= ½).
/// Throws InputError (source `source`) for regions that do not resolve on the garment
/// (pressure_regions.hpp).
std::vector<FitRegion> resolve_fit_regions(const GarmentSimulation& sim,
                                           const PressureRegionSet& regions,
                                           const std::string& source);

/// Statistics of one region: {"name", "faces", "area_m2", "target_pa" {min, max},
/// "target_mmhg", "pressure_pa" {min, median, mean, std, max} (area-weighted median,
/// mean, std), "pressure_mmhg" (same), "spread" (std / mean), "share_in_target",
/// "lift_off_share", "ral_gz_387_class" and "burn_scar_range" / "face_mask_range" of the
/// median, "histogram" {edges_mmhg, area_m2}}; the pressure entries are null for a
/// region without faces. `p` per garment face (Pa), `areas` deformed face areas (m²).
nlohmann::json region_statistics_json(const FitRegion& region, const VecX& p,
                                      const std::vector<double>& areas);

}  // namespace tightfit
