#pragma once
/// Options of the pattern exports (SVG, tiled/full-size PDF, AAMA DXF, pieces.json).
/// Lengths are in metres like everything inside tightfit; the writers convert to mm
/// (or PDF points, 1 mm = 72/25.4 pt) when they write.
#include <map>
#include <string>
#include <vector>

namespace tightfit {

/// Paper for the tiled PDF, portrait.
enum class Paper { A4, Letter };

/// Paper size in mm (A4 210 × 297, Letter 215.9 × 279.4), portrait.
struct PaperSize {
  double width_mm = 0.0;
  double height_mm = 0.0;
};
PaperSize paper_size(Paper paper);

/// How the cut line turns around a convex corner of the sew line.
enum class CornerStyle {
  Mitre,  ///< sharp corner (lines of the two edges meet); rounded beyond `mitre_limit`
  Round,  ///< circular arc of radius = allowance around every convex corner
};

struct PatternExportOptions {
  /// Seam allowance (m) between sew line and cut line on every boundary edge.
  double seam_allowance = 0.010;
  /// Per-seam allowance (m) keyed by the name of a Seam or of a PinnedBoundary; it
  /// applies to the boundary edges of that seam's (or boundary's) polylines. Unknown
  /// names are an InputError.
  std::map<std::string, double> seam_allowances;
  CornerStyle corner_style = CornerStyle::Mitre;
  /// Mitre limit: largest distance of a mitred cut-line corner from its sew-line
  /// corner, in multiples of the allowance (≥ 1); sharper corners are rounded.
  double mitre_limit = 2.0;

  /// Notch spacing (m) along seams: a seam of mean length L gets notches at its two
  /// ends and at fractions k/m, m = max(1, round(L / spacing)); 0 = ends only.
  double notch_spacing = 0.10;

  /// Draw piece names (and annotation text) in SVG and PDF.
  bool piece_labels = true;
  /// Annotation text per piece name (DXF `Annotation:` text, SVG/PDF label line).
  std::map<std::string, std::string> annotations;
  /// Number of times each piece is cut (DXF `Quantity:`), by piece name; default 1.
  std::map<std::string, int> quantities;

  /// Paper of the tiled PDF.
  Paper paper = Paper::A4;
  /// Overlap (m) of neighbouring tiles: the same strip of the layout is on both pages.
  double tile_overlap = 0.010;
  /// Unprinted margin (m) on each side of a tiled page; grid labels are drawn in it.
  double page_margin = 0.012;

  /// Layout (the plane the pieces are placed on): target row width (m), e.g. the
  /// fabric width; a row is wider only when one piece is wider.
  double layout_width = 1.5;
  /// Gap (m) between pieces and around the layout.
  double layout_gap = 0.010;
  /// Add a 10 cm × 10 cm test square to the layout (SVG, PDF: first page).
  bool test_square = true;
  /// A grading nest: piece p is placed at the spot of group nest_group[p], and the
  /// pieces of one group lie on top of each other in their own coordinates (aligned by
  /// the caller, io/pattern_nest.hpp). Empty: every piece has its own spot. Otherwise one
  /// group (≥ 0) per piece.
  std::vector<int> nest_group;
};

}  // namespace tightfit
