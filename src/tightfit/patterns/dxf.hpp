#pragma once
/// DXF export of a pattern in the AAMA / ASTM D6673 layout, ASCII DXF R12 (AC1009),
/// 7-bit ASCII only, drawing units millimetres.
#include <filesystem>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Writes `pattern` as DXF to `path` (atomically):
/// * a 999 comment and HEADER with $ACADVER AC1009, $INSUNITS 4 (mm), $MEASUREMENT 1
///   (metric), $EXTMIN/$EXTMAX;
/// * TABLES: line types CONTINUOUS and DASHED, layers 0, 1, 2, 3, 4, 7, 14, 15, text
///   style STANDARD;
/// * one BLOCK per piece (name: the piece name with characters other than letters,
///   digits, '-' and '_' replaced by '_', made unique), drawn in the piece's own plane
///   (mm, y up): layer 1 cut line (closed POLYLINE, around the trued sew line), layer 2
///   turn points and layer 3 curve points (a POINT at every cut-line vertex: turn point
///   when it turns by more than 30°), layer 14 trued sew line (closed POLYLINE), layer 4
///   notches (a LINE per tick, from the sew line outward), layer 7 grain line (LINE from
///   tail to head) followed by the two strokes of each of its two arrow heads; TEXT
///   placed inside the sew line: layer 1 "Piece Name: <name>", "Quantity: <n>",
///   "Annotation: <text>" (and "Size: <size>" when options.label.size is set), layer 15
///   the other piece label lines (style, fabric, date, notes), the seam and boundary
///   names and "top" marks (rotated along their side);
/// * ENTITIES: the style text on layer 1 below the layout ("Style Name:", "Creation
///   Date:", "Author: tightfit", "Sample Size:", "Units: METRIC"; date and size only when
///   given) and an INSERT of every block at its place in layout_pattern(...) (layout y
///   flipped to point up).
/// Non-ASCII characters in names and texts are written as \U+XXXX.
void write_pattern_dxf(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path);

}  // namespace tightfit
