#pragma once
/// PDF export of a pattern at 1:1 (1 mm = 72/25.4 pt) with cairo: tiled on A4/Letter
/// pages for home printers, or as one full-size page for plotters (A0 and wider).
#include <filesystem>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Points per millimetre in PDF (72 pt per inch).
inline constexpr double kPointsPerMm = 72.0 / 25.4;

/// Tiled PDF (atomically written): the layout (layout_pattern) cut into
/// tile_grid(...).rows × cols portrait pages of `options.paper`, row by row from the
/// top-left tile "A1" (which carries the 10 cm test square). Each page shows its part
/// of the layout inside the page margin; neighbouring pages share `tile_overlap` of the
/// layout, marked by dashed lines and by alignment marks (circle + cross) drawn in
/// layout coordinates on the shared strips so they coincide when the pages are laid
/// over each other. The margins carry the page's grid label (row letter + column
/// number) on every edge with the neighbour's label on that side.
/// InputError on an invalid pattern/options (naming `path`) or an unwritable file.
void write_pattern_pdf_tiled(const Pattern& pattern, const PatternExportOptions& options,
                             const std::filesystem::path& path);

/// One-page PDF whose page is exactly the layout bounding box
/// (layout.width_mm × layout.height_mm), for plotters. Same drawing as the tiles,
/// without tiling marks.
void write_pattern_pdf_full_size(const Pattern& pattern, const PatternExportOptions& options,
                                 const std::filesystem::path& path);

}  // namespace tightfit
