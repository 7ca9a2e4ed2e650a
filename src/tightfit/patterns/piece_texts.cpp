#include "tightfit/patterns/piece_texts.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tightfit {
namespace {

/// Seam labels: height (mm) and gap (mm) between the sew line and the text box.
constexpr double kSeamTextMm = 3.0;
constexpr double kSeamTextGapMm = 1.5;
/// Distance (mm) of the "top" mark from the upper end of a seam side.
constexpr double kTopMarkFromEndMm = 8.0;

/// Points (mm) of a boundary polyline of a piece, in the polyline's order.
std::vector<Vec2> polyline_mm(const PatternPiece& piece, const std::vector<int>& vertices) {
  std::vector<Vec2> out;
  for (int v : vertices) out.push_back(rest_mm(piece, v));
  return out;
}

/// Whether the polyline runs along the piece's outer boundary (not an opening's rim).
bool on_outer_boundary(const PatternPiece& piece, const std::vector<int>& vertices) {
  return !vertices.empty() && std::find(piece.boundary.begin(), piece.boundary.end(),
                                        vertices.front()) != piece.boundary.end();
}

}  // namespace

void add_seam_texts(const Pattern& pattern, const PatternExportOptions& options,
                    std::vector<PieceDrawing>& drawings) {
  for (const Seam& seam : pattern.seams) {
    const auto up = options.seam_last_end_up.find(seam.name);
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      if (!on_outer_boundary(pattern.pieces[static_cast<size_t>(side->piece)], side->vertices))
        continue;
      PieceDrawing& d = drawings[static_cast<size_t>(side->piece)];
      std::vector<Vec2> points =
          polyline_mm(pattern.pieces[static_cast<size_t>(side->piece)], side->vertices);
      d.seam_texts.push_back(
          place_along_side(d.trued_sew_line, points, seam.name, kSeamTextMm, kSeamTextGapMm));
      if (up == options.seam_last_end_up.end()) continue;
      if (!up->second) std::reverse(points.begin(), points.end());
      d.seam_texts.push_back(place_along_side(d.trued_sew_line, points, "top", kSeamTextMm,
                                              kSeamTextGapMm, kTopMarkFromEndMm));
    }
  }
  for (const PinnedBoundary& pin : pattern.pinned) {
    if (!on_outer_boundary(pattern.pieces[static_cast<size_t>(pin.piece)], pin.vertices)) continue;
    PieceDrawing& d = drawings[static_cast<size_t>(pin.piece)];
    d.seam_texts.push_back(place_along_side(
        d.trued_sew_line, polyline_mm(pattern.pieces[static_cast<size_t>(pin.piece)], pin.vertices),
        pin.name, kSeamTextMm, kSeamTextGapMm));
  }
}

std::vector<TextLine> piece_label_lines(const PieceDrawing& d,
                                        const PatternExportOptions& options) {
  const PatternLabelInfo& info = options.label;
  std::vector<TextLine> lines;
  if (!info.style.empty()) lines.push_back({info.style, 3.5, false});
  lines.push_back({d.name, 6.0, true});
  lines.push_back({"cut " + std::to_string(d.quantity), 4.0, false});
  if (info.youngs_modulus > 0.0 && info.thickness > 0.0) {
    std::string fabric = "fabric E ";
    fabric += label_number(info.youngs_modulus * 1e-6, 2);
    fabric += " MPa, ";
    fabric += label_number(info.thickness * kMmPerM, 2);
    fabric += " mm";
    if (info.stretch_min > 0.0 || info.stretch_max > 0.0) {
      fabric += ", stretch ";
      if (info.stretch_max > 0.0) {
        fabric += label_number(info.stretch_min, 2);
        fabric += " to ";
        fabric += label_number(info.stretch_max, 2);
      } else {
        fabric += "from ";
        fabric += label_number(info.stretch_min, 2);
      }
    }
    lines.push_back({fabric, 3.0, false});
  }
  if (!info.fabric_name.empty()) {
    lines.push_back(
        {"fabric " + info.fabric_name + ", " + label_number(info.thickness * kMmPerM, 2) + " mm",
         3.0, false});
    if (info.course_stretch[1] > 0.0 && info.wale_stretch[1] > 0.0)
      lines.push_back({"worn stretch course " + label_number(info.course_stretch[0], 2) + " to " +
                           label_number(info.course_stretch[1], 2) + ", wale " +
                           label_number(info.wale_stretch[0], 2) + " to " +
                           label_number(info.wale_stretch[1], 2),
                       3.0, false});
  }
  if (!info.size.empty()) lines.push_back({"size " + info.size, 3.0, false});
  if (!info.date.empty()) lines.push_back({info.date, 3.0, false});
  if (!d.annotation.empty()) lines.push_back({d.annotation, 3.0, false});
  if (const auto notes = options.piece_notes.find(d.name); notes != options.piece_notes.end())
    for (const std::string& note : notes->second)
      if (!note.empty()) lines.push_back({note, 3.0, false});
  return lines;
}

std::string label_number(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  std::ostringstream out;
  out << std::round(value * scale) / scale;
  return out.str();
}

}  // namespace tightfit
