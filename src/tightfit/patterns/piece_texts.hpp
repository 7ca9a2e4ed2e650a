#pragma once
/// The text drawn on pattern pieces, in mm in the piece's plane: seam and boundary
/// names along their sides, "top" marks, and the piece label's lines.
#include <string>
#include <vector>

#include "tightfit/patterns/drawing.hpp"

namespace tightfit {

/// Adds to drawings[p].seam_texts (placed by place_along_side inside the trued sew
/// line, 3 mm high, 1.5 mm from the sew line): the seam's name along both of its sides,
/// "top" 8 mm from the upper end of each side of the seams in
/// options.seam_last_end_up, and each pinned boundary's name along it. Seams and
/// boundaries on an opening's rim are left out. `drawings` are in piece order with
/// their trued sew lines computed.
void add_seam_texts(const Pattern& pattern, const PatternExportOptions& options,
                    std::vector<PieceDrawing>& drawings);

/// The piece label's lines: style (3.5 mm), piece name (6 mm, bold), "cut N" (4 mm),
/// fabric "fabric E <MPa> MPa, <mm> mm[, stretch <min> to <max> | from <min>]", "size
/// <size>", date, annotation, then options.piece_notes of the piece (3 mm); lines
/// without content are left out.
std::vector<TextLine> piece_label_lines(const PieceDrawing& d, const PatternExportOptions& options);

/// Number formatting of the labels: `value` rounded to `decimals` digits, trailing
/// zeros dropped ("5.4", "10", "0.5").
std::string label_number(double value, int decimals);

}  // namespace tightfit
