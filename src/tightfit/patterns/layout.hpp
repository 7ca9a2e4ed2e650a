#pragma once
/// Places the pieces on one plane without overlap (rows of bounding boxes) and cuts
/// that plane into printable tiles. Layout coordinates are mm with the origin at the
/// top-left corner and y pointing DOWN (as on paper, SVG and cairo); pieces keep
/// their orientation (so their grain) and are mirrored in y only by the change of axes.
#include <string>
#include <vector>

#include "tightfit/patterns/drawing.hpp"

namespace tightfit {

/// Side of the test square (mm).
inline constexpr double kTestSquareMm = 100.0;

/// An axis-aligned box (mm).
struct Box2 {
  Vec2 min = Vec2::Zero();
  Vec2 max = Vec2::Zero();
  double width() const { return max.x() - min.x(); }
  double height() const { return max.y() - min.y(); }
  /// Whether the box [lo, hi] meets this one (touching counts).
  bool meets(const Vec2& lo, const Vec2& hi) const {
    return lo.x() <= max.x() && hi.x() >= min.x() && lo.y() <= max.y() && hi.y() >= min.y();
  }
};

struct PatternLayout {
  double width_mm = 0.0;  ///< layout bounding box, including the gap around it
  double height_mm = 0.0;
  /// Per piece: layout point = (x + offset.x, offset.y − y) for a piece point (x, y) in mm.
  std::vector<Vec2> offsets;
  /// Per piece: its cut line's bounding box in layout coordinates.
  std::vector<Box2> piece_boxes;
  bool has_test_square = false;
  Box2 test_square;  ///< the 100 mm test square in layout coordinates (if present)

  /// Layout coordinates (mm, y down) of point `q` (mm, y up) of piece `piece`.
  Vec2 to_layout(size_t piece, const Vec2& q) const {
    return Vec2(q.x() + offsets[piece].x(), offsets[piece].y() - q.y());
  }
};

/// Shelf layout: the test square first (if enabled), then the pieces in order, left
/// to right in rows of at most `options.layout_width`, `options.layout_gap` apart and
/// around the border. Boxes never overlap, except in a nest (`options.nest_group`):
/// the pieces of one group share one spot and its box (the union of theirs).
PatternLayout layout_pattern(const std::vector<PieceDrawing>& pieces,
                             const PatternExportOptions& options);

/// How a layout is cut into pages. Tile (row, col) shows the layout rectangle
/// [col·step_x, col·step_x + content_width] × [row·step_y, row·step_y + content_height]
/// inside the page margin; neighbouring tiles share `overlap_mm` of the layout.
struct TileGrid {
  PaperSize page;
  double margin_mm = 0.0;
  double overlap_mm = 0.0;
  double content_width_mm = 0.0;   ///< page width − 2 margins
  double content_height_mm = 0.0;  ///< page height − 2 margins
  int rows = 0;
  int cols = 0;
  double step_x_mm() const { return content_width_mm - overlap_mm; }
  double step_y_mm() const { return content_height_mm - overlap_mm; }
};

/// cols = max(1, ceil((W − overlap) / (content width − overlap))), rows likewise with
/// the heights, for a W × H layout.
TileGrid tile_grid(const PatternLayout& layout, const PatternExportOptions& options);

/// The layout rectangle tile (row, col) shows (mm), grown by `slack_mm` on every side.
Box2 tile_box(const TileGrid& grid, int row, int col, double slack_mm);

/// Consecutive edges of a closed outline: edges first … first + count − 1, edge i
/// joining vertex i to vertex (i + 1) mod n, starting `arc_length` (mm) along the
/// outline from vertex 0.
struct OutlineRun {
  size_t first = 0;
  size_t count = 0;
  double arc_length = 0.0;
};

/// The runs of edges of the closed outline `outline` (layout mm, n vertices) whose
/// bounding boxes meet `box`, in order of the outline; a run never wraps past vertex 0,
/// so every edge seen → one run {0, n, 0}; none → no run.
std::vector<OutlineRun> outline_runs(const std::vector<Vec2>& outline, const Box2& box);

/// Label of tile (row, col), 0-based: rows are letters (A..Z, AA, AB, ...), columns
/// numbers from 1: (0, 0) → "A1", (1, 2) → "B3".
std::string tile_label(int row, int col);

}  // namespace tightfit
