#pragma once
/// pieces.json: every pattern piece with its mesh and outlines, and the seams and pinned
/// boundaries between them, so seam correspondences survive the export; and its reader.
#include <filesystem>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/report/seam_statistics.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Writes pieces.json (atomically): the pattern's record (scene/pattern_record.hpp) with
/// the derived keys below beside its own. Format (version 1):
/// {
///   "format": "tightfit-pieces", "version": 1,
///   "units": {"rest": "m", "outlines": "mm"},
///   "seam_allowance_m": default allowance,
///   "pieces": [{ "name", "quantity",
///       "rest": [[x, y], ...]          (m, n×2; the mesh vertices),
///       "triangles": [[i, j, k], ...]  (counter-clockwise),
///       "boundary": [...]               (counter-clockwise loop of vertex indices),
///       "corners": [...], "grain": [gx, gy],
///       "sew_line_mm": [[x, y], ...]   (= rest[boundary] × 1000),
///       "cut_line_mm": [[x, y], ...]   (counter-clockwise; around the trued sew line the
///                                       writers draw, patterns/truing.hpp),
///       "allowance_mm": [...]          (per sew-line edge boundary[k] → boundary[k+1]),
///       "grain_line_mm": [[x, y], [x, y]] (tail, head),
///       "notches_mm": [{"seam", "side": "a"|"b", "index", "sew": [x, y], "cut": [x, y],
///                       "style": "single"|"double"}] }],
///     ("cut": the outer end of the notch, notch depth from "sew")
///   "seams": [{"name", "a": {"piece", "piece_name", "vertices"}, "b": {...},
///              "length_a_mm", "length_b_mm", "mismatch_mm",   (sewing lengths of the sides)
///              "fit": {"sewn_length_mm", "stretch_a", "stretch_b", "traction_mean_n_per_m",
///                      "traction_max_n_per_m", "traction_total_n"} (only with `fit_seams`)}],
///   "pinned": [{"name", "piece", "piece_name", "vertices"}]
/// }
/// Seam side vertex i of "a" meets vertex i of "b". Piece references are indices into
/// "pieces" ("piece_name" is informative). `fit_seams` (one per seam of the pattern, in
/// its order; report/seam_statistics.hpp) adds each seam's state on the simulated fit.
/// InputError for an invalid pattern/options.
void write_pieces_json(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path,
                       const std::vector<SeamStatistics>* fit_seams = nullptr);

/// Reads the pattern (pieces' name, rest, triangles, boundary, holes, corners, grain;
/// seams; pinned boundaries) back from pieces.json with pattern_record_from_json. The
/// derived fields (outlines, notches, allowances, quantity, piece names of seam sides,
/// seam lengths and fit) are accepted and ignored. InputError naming the file and JSON
/// path for a malformed file, and validate_pattern's errors for an invalid pattern.
Pattern read_pieces_json(const std::filesystem::path& path);

}  // namespace tightfit
