#include "tightfit/patterns/outputs.hpp"

#include <algorithm>
#include <functional>

#include "tightfit/common/parallel.hpp"
#include "tightfit/patterns/dxf.hpp"
#include "tightfit/patterns/json.hpp"
#include "tightfit/patterns/pdf.hpp"
#include "tightfit/patterns/svg.hpp"

namespace tightfit {

std::vector<std::string> write_pattern_files(const std::filesystem::path& folder,
                                             const Pattern& pattern, PatternExportOptions options,
                                             const std::vector<SeamStatistics>* fit_seams) {
  PatternExportOptions a4 = options, letter = options;
  a4.paper = Paper::kA4;
  letter.paper = Paper::kLetter;
  // Independent files, dealt round-robin to the threads (the two tiled PDFs, the
  // costliest, first): the same bytes as written one after the other.
  const std::vector<std::function<void()>> writers = {
      [&] { write_pattern_pdf_tiled(pattern, a4, folder / "pattern_a4.pdf"); },
      [&] { write_pattern_pdf_tiled(pattern, letter, folder / "pattern_letter.pdf"); },
      [&] { write_pattern_dxf(pattern, letter, folder / "pattern.dxf"); },
      [&] { write_pattern_pdf_full_size(pattern, letter, folder / "pattern_full.pdf"); },
      [&] { write_pieces_json(pattern, letter, folder / "pieces.json", fit_seams); },
      [&] { write_pattern_svg(pattern, options, folder / "pattern.svg"); },
  };
  const int threads = std::min(thread_count(), static_cast<int>(writers.size()));
  run_on_threads(threads, [&](int t) {
    for (std::size_t w = static_cast<std::size_t>(t); w < writers.size();
         w += static_cast<std::size_t>(threads))
      writers[w]();
  });
  return {"pattern.svg",      "pattern_a4.pdf", "pattern_letter.pdf",
          "pattern_full.pdf", "pattern.dxf",    "pieces.json"};
}

nlohmann::json garment_build_report(const GarmentBuild& build) {
  nlohmann::json j;
  auto& pieces = j["pieces"];
  pieces = nlohmann::json::array();
  for (const PieceReport& p : build.pieces)
    pieces.push_back({{"name", p.name},
                      {"vertices", p.vertices},
                      {"triangles", p.triangles},
                      {"min_angle_deg", p.min_angle_deg},
                      {"scale", {{"along_grain", p.scale.along}, {"across_grain", p.scale.across}}},
                      {"flattening",
                       {{"area_3d_m2", p.distortion.area_3d},
                        {"area_2d_m2", p.distortion.area_2d},
                        {"area_error", p.distortion.area_error},
                        {"mean_area_distortion", p.distortion.mean_area_distortion},
                        {"max_area_distortion", p.distortion.max_area_distortion},
                        {"mean_angle_error_deg", p.distortion.mean_angle_error_deg},
                        {"max_angle_error_deg", p.distortion.max_angle_error_deg},
                        {"flipped_triangles", p.distortion.flipped}}}});
  auto& seams = j["seams"];
  seams = nlohmann::json::array();
  for (const SeamReport& s : build.seams)
    seams.push_back({{"name", s.name},
                     {"length_3d_m", s.length_3d},
                     {"length_side_a_m", s.length_a},
                     {"length_side_b_m", s.length_b},
                     {"relative_difference", s.relative_difference},
                     {"vertices_per_side", s.vertices}});
  double max_dist = 0;
  for (double d : build.projection_distance) max_dist = std::max(max_dist, d);
  j["max_projection_distance_m"] = max_dist;
  return j;
}

}  // namespace tightfit
