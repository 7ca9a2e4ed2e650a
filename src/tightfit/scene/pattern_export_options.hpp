#pragma once
/// Options of the pattern exports (SVG, tiled/full-size PDF, AAMA DXF, pieces.json).
/// Lengths are in metres like everything inside tightfit; the writers convert to mm
/// (or PDF points, 1 mm = 72/25.4 pt) when they write.
#include <array>
#include <map>
#include <string>
#include <vector>

namespace tightfit {

/// Paper for the tiled PDF, portrait.
enum class Paper { kA4, kLetter };

/// Paper size in mm (A4 210 × 297, Letter 215.9 × 279.4), portrait.
struct PaperSize {
  double width_mm = 0.0;
  double height_mm = 0.0;
};
PaperSize paper_size(Paper paper);

/// How the cut line turns around a convex corner of the sew line.
enum class CornerStyle {
  kMitre,  ///< sharp corner (lines of the two edges meet); rounded beyond `mitre_limit`
  kRound,  ///< circular arc of radius = allowance around every convex corner
};

/// How the notches of a seam are cut: the trade marks front seams with one tick and
/// back seams with two, so that a front piece cannot be sewn to a back one.
enum class NotchStyle {
  kSingle,  ///< one tick
  kDouble,  ///< two parallel ticks `double_notch_gap` apart, centred on the notch position
};

/// What the piece and style labels say besides the piece's own name and quantity.
struct PatternLabelInfo {
  /// Style (design) name; empty: no style line.
  std::string style;
  /// Size or body the pattern was made for; empty: no size line.
  std::string size;
  /// Creation date, UTC, "YYYY-MM-DD"; empty: no date line.
  std::string date;
  /// Fabric Young's modulus (Pa) and thickness (m); 0: no fabric line.
  double youngs_modulus = 0.0;
  double thickness = 0.0;
  /// A measured knit's name (fabric line "fabric NAME, t mm" instead of E); empty: none.
  std::string fabric_name;
  /// The worn stretch across the grain (course) and along it (wale) of the fitted
  /// garment, 5th to 95th area percentile, [lo, hi]; {0, 0}: not known (no line).
  std::array<double, 2> course_stretch = {0.0, 0.0};
  std::array<double, 2> wale_stretch = {0.0, 0.0};
  /// Stretch range (stretched / rest length) the pattern was designed for; 0: not
  /// given (only a minimum: "stretch from min").
  double stretch_min = 0.0;
  double stretch_max = 0.0;
};

struct PatternExportOptions {
  /// Seam allowance (m) between sew line and cut line on every boundary edge.
  double seam_allowance = 0.010;
  /// Per-seam allowance (m) keyed by the name of a Seam or of a PinnedBoundary; it
  /// applies to the boundary edges of that seam's (or boundary's) polylines. Unknown
  /// names are an InputError.
  std::map<std::string, double> seam_allowances;
  CornerStyle corner_style = CornerStyle::kMitre;
  /// Mitre limit: largest distance of a mitred cut-line corner from its sew-line
  /// corner, in multiples of the allowance (≥ 1); sharper corners are rounded.
  double mitre_limit = 2.0;

  /// Notch spacing (m) along seams: a seam of mean length L gets notches at its two
  /// ends and at fractions k/m, m = max(1, round(L / spacing)); 0 = ends only.
  double notch_spacing = 0.10;
  /// Notch depth (m) from the sew line outward (the trade cuts 3–6 mm). At an edge
  /// whose allowance is smaller the notch stops at the cut line: depth = min(notch_depth,
  /// allowance of that edge).
  double notch_depth = 0.004;
  /// Distance (m) between the two ticks of a double notch.
  double double_notch_gap = 0.003;
  /// Notch style by seam name; seams not named get Single. Unknown names are an
  /// InputError.
  std::map<std::string, NotchStyle> seam_notch_styles;
  /// Which end of a seam is higher on the body, by seam name: true when the seams'
  /// last side vertices (a.vertices.back() ↔ b.vertices.back()) are the upper end,
  /// false when the first are. Seams not named get no "up" mark.
  std::map<std::string, bool> seam_last_end_up;
  /// Truing tolerance (m): the drawn sew and cut lines follow a smooth curve through
  /// the boundary within this distance of it (patterns/truing.hpp); 0 draws the
  /// boundary polyline itself. pieces.json keeps the untrued outline.
  double true_tolerance = 0.0003;

  /// Draw piece names (and annotation text) in SVG and PDF.
  bool piece_labels = true;
  /// Annotation text per piece name (DXF `Annotation:` text, SVG/PDF label line).
  std::map<std::string, std::string> annotations;
  /// Label seam sides with the seam's name, pinned boundaries with theirs, and mark
  /// the upper end of seams (SVG, PDF, DXF).
  bool seam_labels = true;
  /// Style, size, date and fabric lines of the piece labels and the DXF style text.
  PatternLabelInfo label;
  /// Extra label lines per piece name, drawn below the piece label.
  std::map<std::string, std::vector<std::string>> piece_notes;
  /// Number of times each piece is cut (DXF `Quantity:`), by piece name; default 1.
  std::map<std::string, int> quantities;

  /// Paper of the tiled PDF.
  Paper paper = Paper::kA4;
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
  /// the caller, patterns/nest.hpp). Empty: every piece has its own spot. Otherwise one
  /// group (≥ 0) per piece.
  std::vector<int> nest_group;
};

}  // namespace tightfit
