#pragma once
/// What is drawn for each pattern piece, in millimetres in the piece's own plane
/// (x right, y up, like PatternPiece::rest × 1000): sew line (as given and trued), cut
/// line, notches (single or double ticks), grain line, seam and boundary names, "top"
/// marks and the piece label. All pattern writers draw from this.
#include <array>
#include <string>
#include <vector>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/patterns/labels.hpp"
#include "tightfit/patterns/offset.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Millimetres per metre: pattern files are drawn in mm, tightfit computes in m.
inline constexpr double kMmPerM = 1000.0;

/// Rest position (mm) of vertex `v` of `piece`.
inline Vec2 rest_mm(const PatternPiece& piece, int v) {
  return piece.rest.row(v).transpose() * kMmPerM;
}

/// A notch: a short tick (or two, NotchStyle::kDouble) perpendicular to the sew line,
/// from the sew line outward, `depth` = min(notch depth, the edge's allowance) long.
/// Notches with the same `seam` and `index` on the two sides of a seam are sewn
/// together.
struct Notch {
  std::string seam;  ///< name of the seam
  int side = 0;      ///< 0: on seam side a, 1: on side b
  int index = 0;     ///< 0 at the first vertex of the seam sides, count−1 at the last
  Vec2 sew;          ///< mm, on the sew line (and exactly on the trued sew line)
  Vec2 cut;          ///< mm, outer end of the notch centre (sew + depth × outward normal)
  NotchStyle style = NotchStyle::kSingle;
  /// mm, the ticks to cut, each from the sew line outward: one through `sew` (Single)
  /// or two, ± double_notch_gap / 2 along the sew line (Double) — at the seam's first
  /// and last notch one at `sew` and one double_notch_gap further into the seam, so
  /// that both stay on the seam.
  std::vector<std::array<Vec2, 2>> ticks;
};

struct PieceDrawing {
  std::string name;
  int quantity = 1;
  std::string annotation;
  /// mm, counter-clockwise; point k is rest vertex boundary[k].
  Polygon2 sew_line;
  /// mm, allowance of sew-line edge k (point k → point k+1).
  std::vector<double> allowance;
  /// mm, counter-clockwise: the sew line the writers draw, trued (patterns/truing.hpp,
  /// tolerance `true_tolerance`) through the kept points: corners, sharp turns, seam and
  /// pinned-boundary ends and notch positions. Equals sew_line plus the notch points
  /// when truing is off.
  Polygon2 trued_sew_line;
  /// mm, counter-clockwise, outward offset of the trued sew line by the allowances.
  Polygon2 cut_line;
  /// mm, clockwise: the openings (rest vertices holes[h][k]); cut on their sew line,
  /// without allowance (finished with binding, as the trade finishes mask openings).
  std::vector<Polygon2> holes;
  std::vector<Notch> notches;
  /// mm, grain line through the centroid; the arrow points at `grain_end`.
  Vec2 grain_start = Vec2::Zero();
  Vec2 grain_end = Vec2::Zero();
  /// mm, area centroid of the sew line (labels are placed here).
  Vec2 centroid = Vec2::Zero();
  /// The piece label's lines: style, piece name, "cut N", fabric, size, date,
  /// annotation, then options.piece_notes of this piece (lines with no content left out).
  std::vector<TextLine> label_lines;
  /// label_lines placed inside trued_sew_line (place_text_block).
  std::vector<PlacedText> label;
  /// Seam names along both sides of each seam, pinned-boundary names along theirs and
  /// "top" at the upper end of seam sides (options.seam_last_end_up), inside the piece.
  std::vector<PlacedText> seam_texts;
};

/// Arc-length positions of notches along one seam: for k = 0..m the notch k sits at
/// segment `segment[k]` (between side vertices segment and segment+1) at local
/// parameter `t[k]` ∈ [0, 1], the same on both sides so that notch k of side a meets
/// notch k of side b under the seam's vertex correspondence. The target fraction k/m
/// is measured on the mean of the two sides' normalised arc lengths, which equals the
/// arc-length fraction on both sides when their vertices are spaced proportionally.
/// m = max(1, round(mean side length / spacing)), m = 1 when `spacing` is 0.
struct SeamNotchParameters {
  std::vector<int> segment;
  std::vector<double> t;
};
SeamNotchParameters seam_notch_parameters(const std::vector<Vec2>& side_a,
                                          const std::vector<Vec2>& side_b, double spacing);

/// Validates `pattern` and `options` (InputError naming `source`) and computes every
/// piece's drawing, in piece order.
std::vector<PieceDrawing> draw_pattern_pieces(const Pattern& pattern,
                                              const PatternExportOptions& options,
                                              const std::string& source);

}  // namespace tightfit
