#pragma once
/// SVG export of a pattern at 1:1: the root is sized in mm (width="…mm", viewBox in
/// mm), one group per piece with cut line (solid), trued sew line (dashed), notches,
/// double-headed grain line, seam names (class "seam") and the piece label, plus a 10 cm
/// test square.
#include <filesystem>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Writes `pattern` as SVG to `path` (atomically). Piece group ids are
/// "piece-<name>" (characters other than letters, digits, '-', '_', '.' become '_';
/// a numeric suffix keeps them unique); the test square is the group "test-square".
/// The layout is layout_pattern(draw_pattern_pieces(...)). InputError on an invalid
/// pattern or options (naming `path`) or when the file cannot be written.
void write_pattern_svg(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path);

}  // namespace tightfit
