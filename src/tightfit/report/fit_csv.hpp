#pragma once
/// The fit per garment triangle as a CSV table (garment.csv, and garment_pose_NAME.csv
/// for each pose), for spreadsheets and scripts: one row per garment face with
///   face, piece, area_m2 (deformed), stretch_max, stretch_min, stretch_course,
///   stretch_wale (across and along the grain), regime (slack, wrinkled, taut),
///   tension_max_n_per_m, pressure_pa, pressure_mmhg
/// and, for a pose, sliding_excess_n (the face's mean tangential force above the
/// friction limit, N). Numbers are written with 9 significant digits, '.' decimal.
#include <filesystem>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/physics/cloth_analysis.hpp"

namespace tightfit {

/// Writes the table of `elements` (one per garment face of `garment`) with the pressure
/// per face `pressure_pa` (Pa) and, when not null, `sliding_excess_n` per face (N).
/// The file is written atomically.
void write_fit_csv(const std::filesystem::path& file, const Garment& garment,
                   const std::vector<ClothElementFit>& elements, const VecX& pressure_pa,
                   const VecX* sliding_excess_n = nullptr);

}  // namespace tightfit
