#pragma once
/// A quick SVG drawing of pattern pieces for debugging: 1:1 scale (millimetres), one
/// group per piece with its mesh, outline, seam sides (one colour per seam, labelled),
/// pinned boundaries (dashed blue), corners, grain arrow and name. Pieces are placed
/// in rows, left to right. (Production exports with seam allowances and notches live in
/// the io layer.)
#include <filesystem>
#include <string>

#include "tightfit/garment/pattern.hpp"

namespace tightfit {

struct SvgOptions {
  double gap = 0.03;            ///< space between pieces (m)
  double row_width = 1.5;       ///< pieces wrap to a new row beyond this width (m)
  bool draw_triangles = true;   ///< draw the piece meshes
};

/// The SVG document as text.
std::string pattern_svg(const Pattern& pattern, const SvgOptions& options = {});

/// Writes pattern_svg atomically to `path`.
void write_pattern_svg(const std::filesystem::path& path, const Pattern& pattern,
                       const SvgOptions& options = {});

}  // namespace tightfit
