#pragma once
/// DXF export of a pattern in the AAMA / ASTM D6673 layout, ASCII DXF R12 (AC1009),
/// 7-bit ASCII only, drawing units millimetres.
#include <filesystem>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/io/pattern_export_options.hpp"

namespace tightfit {

/// Writes `pattern` as DXF to `path` (atomically):
/// * a 999 comment and HEADER with $ACADVER AC1009, $INSUNITS 4 (mm), $MEASUREMENT 1
///   (metric), $EXTMIN/$EXTMAX;
/// * TABLES: line types CONTINUOUS and DASHED, layers 0, 1, 4, 7, 14, text style STANDARD;
/// * one BLOCK per piece (name: the piece name with characters other than letters,
///   digits, '-' and '_' replaced by '_', made unique), drawn in the piece's own plane
///   (mm, y up): layer 1 cut line (closed POLYLINE), layer 14 sew line (closed
///   POLYLINE), layer 4 notches (LINE from sew line to cut line), layer 7 grain line
///   (LINE, from tail to head), layer 1 TEXT "Piece Name: <name>", "Quantity: <n>",
///   "Annotation: <text>";
/// * ENTITIES: an INSERT of every block at its place in layout_pattern(...) (layout y
///   flipped to point up).
/// Non-ASCII characters in names and texts are written as \U+XXXX.
void write_pattern_dxf(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path);

}  // namespace tightfit
