#pragma once
/// The pattern files a pattern maker cuts from, written together: pattern.svg (1:1),
/// pattern_a4.pdf and pattern_letter.pdf (tiled), pattern_full.pdf (one plotter page),
/// pattern.dxf (AAMA/ASTM D6673, ASCII R12) and pieces.json (outlines, meshes, seams).
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tightfit/garment/garment_builder.hpp"
#include "tightfit/report/seam_statistics.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Writes the six pattern files into `folder` (each atomically). `fit_seams` (one per
/// seam) adds the seams' state on the fit to pieces.json. Returns their names.
std::vector<std::string> write_pattern_files(
    const std::filesystem::path& folder, const Pattern& pattern, PatternExportOptions options = {},
    const std::vector<SeamStatistics>* fit_seams = nullptr);

/// Flattening and seam reports of a built garment as JSON: per piece area and angle
/// distortion, scale-down, mesh size and smallest angle; per seam the 3D and 2D side
/// lengths and their relative difference.
nlohmann::json garment_build_report(const GarmentBuild& build);

}  // namespace tightfit
