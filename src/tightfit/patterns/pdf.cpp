#include "tightfit/patterns/pdf.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"

namespace tightfit {
namespace {

using Cairo = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

/// Slack around a tile's rectangle (mm) within which lines count as seen: more than
/// half the widest line (0.4 mm) and its round caps.
constexpr double kTileSlackMm = 1.0;

/// Whether every edge of the closed outline `q` runs along an axis (to 0.01 mm). cairo
/// writes an axis-aligned rectangle as a PDF rectangle, dashed from its top-left corner
/// whatever its first vertex: such outlines are drawn whole on tiles too (they are cheap).
bool axis_aligned(const std::vector<Vec2>& q) {
  for (size_t i = 0; i < q.size(); ++i) {
    const Vec2 d = (q[(i + 1) % q.size()] - q[i]).cwiseAbs();
    if (std::min(d.x(), d.y()) > 0.01) return false;
  }
  return true;
}

/// Strokes the closed `polygon` of piece `p` with the current source and width, dashed
/// by `dash` (empty: solid). With a tile's `view` (layout mm), only the runs of edges
/// it sees are drawn, each dashed from its arc-length offset along the outline, so the
/// dashes fall where the whole outline (the full-size page) puts them: a piece spanning
/// many pages does not carry its whole outline on each.
void stroke_outline(cairo_t* cr, const PatternLayout& layout, size_t p, const Polygon2& polygon,
                    const std::vector<double>& dash, const Box2* view) {
  const size_t n = polygon.size();
  std::vector<Vec2> q(n);
  for (size_t i = 0; i < n; ++i) q[i] = layout.to_layout(p, polygon[i]);
  const int dashes = static_cast<int>(dash.size());
  if (!view || axis_aligned(q)) {
    cairo_set_dash(cr, dash.data(), dashes, 0.0);
    for (size_t i = 0; i < n; ++i) {
      if (i == 0) {
        cairo_move_to(cr, q[i].x(), q[i].y());
      } else {
        cairo_line_to(cr, q[i].x(), q[i].y());
      }
    }
    cairo_close_path(cr);
    cairo_stroke(cr);
    return;
  }
  for (const OutlineRun& run : outline_runs(q, *view)) {
    cairo_set_dash(cr, dash.data(), dashes, run.arc_length);
    cairo_move_to(cr, q[run.first].x(), q[run.first].y());
    for (size_t k = 1; k <= run.count; ++k) {
      const Vec2& v = q[(run.first + k) % n];
      cairo_line_to(cr, v.x(), v.y());
    }
    cairo_stroke(cr);
  }
}

void segment(cairo_t* cr, const Vec2& a, const Vec2& b) {
  cairo_move_to(cr, a.x(), a.y());
  cairo_line_to(cr, b.x(), b.y());
}

void show_text(cairo_t* cr, const Vec2& at, double size_mm, const std::string& text,
               bool bold = false, double align = 0.0) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_mm);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  cairo_move_to(cr, at.x() - align * extents.x_advance, at.y());
  cairo_show_text(cr, text.c_str());
}

/// A placed text (piece plane) at its place in the layout, rotated along its direction.
void show_placed(cairo_t* cr, const PatternLayout& layout, size_t p, const PlacedText& t) {
  const Vec2 at = layout.to_layout(p, t.at);
  cairo_save(cr);
  cairo_translate(cr, at.x(), at.y());
  cairo_rotate(cr, std::atan2(-t.direction.y(), t.direction.x()));
  show_text(cr, Vec2::Zero(), t.height, t.text, t.bold);
  cairo_restore(cr);
}

/// An open arrow head at `tip`, pointing away from `from`.
void arrow_head(cairo_t* cr, const Vec2& tip, const Vec2& from) {
  const Vec2 back = (from - tip).normalized() * 6.0;
  const Vec2 side(-back.y() * 0.4, back.x() * 0.4);
  segment(cr, tip + back + side, tip);
  cairo_line_to(cr, (tip + back - side).x(), (tip + back - side).y());
}

/// Draws the whole layout in layout mm (the current matrix maps mm to the page).
/// On a tile, `view` leaves out what the tile does not see (nullptr: draw everything).
void draw_layout(cairo_t* cr, const std::vector<PieceDrawing>& pieces, const PatternLayout& layout,
                 const PatternExportOptions& options, const Box2* view) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (layout.has_test_square &&
      (!view || view->meets(layout.test_square.min, layout.test_square.max))) {
    const Box2& s = layout.test_square;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.3);
    cairo_rectangle(cr, s.min.x(), s.min.y(), kTestSquareMm, kTestSquareMm);
    cairo_stroke(cr);
    show_text(cr, s.min + Vec2(8.0, 45.0), 7.0, "10 cm", true);
    show_text(cr, s.min + Vec2(8.0, 55.0), 4.0, "test square: measure 100 mm");
  }
  for (size_t p = 0; p < pieces.size(); ++p) {
    const PieceDrawing& piece = pieces[p];
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.4);
    stroke_outline(cr, layout, p, piece.cut_line, {}, view);
    for (const Polygon2& hole : piece.holes) stroke_outline(cr, layout, p, hole, {}, view);
    cairo_set_source_rgb(cr, 0.1, 0.31, 0.82);
    cairo_set_line_width(cr, 0.25);
    stroke_outline(cr, layout, p, piece.trued_sew_line, {3.0, 1.5}, view);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    cairo_set_source_rgb(cr, 0.75, 0, 0);
    cairo_set_line_width(cr, 0.4);
    for (const Notch& n : piece.notches) {
      for (const auto& tick : n.ticks)
        segment(cr, layout.to_layout(p, tick[0]), layout.to_layout(p, tick[1]));
    }
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0.48, 0.18);
    cairo_set_line_width(cr, 0.35);
    const Vec2 a = layout.to_layout(p, piece.grain_start);
    const Vec2 b = layout.to_layout(p, piece.grain_end);
    segment(cr, a, b);
    if ((b - a).norm() > 0.0) {
      arrow_head(cr, b, a);
      arrow_head(cr, a, b);
    }
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.1, 0.31, 0.82);
    for (const PlacedText& t : piece.seam_texts) show_placed(cr, layout, p, t);
    if (options.piece_labels) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      for (const PlacedText& t : piece.label) show_placed(cr, layout, p, t);
    }
  }
}

/// Circle-and-cross marks on the strips shared by neighbouring tiles (layout mm).
/// On a tile, `view` leaves out the marks it does not see.
void draw_alignment_marks(cairo_t* cr, const TileGrid& grid, const Box2& view) {
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.2);
  auto mark = [&](double x, double y) {
    if (!view.meets(Vec2(x - 4.0, y - 4.0), Vec2(x + 4.0, y + 4.0))) return;
    cairo_new_sub_path(cr);
    cairo_arc(cr, x, y, 2.5, 0.0, 6.283185307179586);
    segment(cr, Vec2(x - 4.0, y), Vec2(x + 4.0, y));
    segment(cr, Vec2(x, y - 4.0), Vec2(x, y + 4.0));
  };
  const double half = 0.5 * grid.overlap_mm;
  for (int c = 0; c + 1 < grid.cols; ++c) {
    const double x = (c + 1) * grid.step_x_mm() + half;
    for (int r = 0; r < grid.rows; ++r) {
      for (double f : {0.25, 0.5, 0.75}) mark(x, r * grid.step_y_mm() + f * grid.content_height_mm);
    }
  }
  for (int r = 0; r + 1 < grid.rows; ++r) {
    const double y = (r + 1) * grid.step_y_mm() + half;
    for (int c = 0; c < grid.cols; ++c) {
      for (double f : {0.25, 0.5, 0.75}) mark(c * grid.step_x_mm() + f * grid.content_width_mm, y);
    }
  }
  cairo_stroke(cr);
}

/// Page furniture of tile (r, c) in page mm: content frame, overlap lines, labels.
void draw_tile_furniture(cairo_t* cr, const TileGrid& grid, int r, int c) {
  const double m = grid.margin_mm;
  const double w = grid.content_width_mm;
  const double h = grid.content_height_mm;
  const double o = grid.overlap_mm;
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
  cairo_set_line_width(cr, 0.2);
  cairo_rectangle(cr, m, m, w, h);
  cairo_stroke(cr);
  const double dash[] = {2.0, 2.0};
  cairo_set_dash(cr, dash, 2, 0.0);
  if (c > 0) segment(cr, Vec2(m + o, m), Vec2(m + o, m + h));
  if (c + 1 < grid.cols) segment(cr, Vec2(m + w - o, m), Vec2(m + w - o, m + h));
  if (r > 0) segment(cr, Vec2(m, m + o), Vec2(m + w, m + o));
  if (r + 1 < grid.rows) segment(cr, Vec2(m, m + h - o), Vec2(m + w, m + h - o));
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_set_source_rgb(cr, 0, 0, 0);
  const std::string self = tile_label(r, c);
  const double size = std::min(4.0, 0.45 * m);
  const double baseline = 0.5 * m + 0.35 * size;
  auto edge_text = [&](const std::string& neighbour, const std::string& where) {
    return self + (neighbour.empty() ? "" : "   (" + neighbour + " " + where + ")");
  };
  const std::string above = r > 0 ? tile_label(r - 1, c) : "";
  const std::string below = r + 1 < grid.rows ? tile_label(r + 1, c) : "";
  const std::string left = c > 0 ? tile_label(r, c - 1) : "";
  const std::string right = c + 1 < grid.cols ? tile_label(r, c + 1) : "";
  show_text(cr, Vec2(m + 0.5 * w, baseline), size, edge_text(above, "above"), true, 0.5);
  show_text(cr, Vec2(m + 0.5 * w, grid.page.height_mm - m + baseline), size,
            edge_text(below, "below"), true, 0.5);
  show_text(cr, Vec2(m, baseline), 0.7 * size,
            "page " + std::to_string(r * grid.cols + c + 1) + "/" +
                std::to_string(grid.rows * grid.cols) + "  scale 1:1");
  cairo_save(cr);
  cairo_translate(cr, baseline, m + 0.5 * h);
  cairo_rotate(cr, -1.5707963267948966);
  show_text(cr, Vec2(0.0, 0.0), size, edge_text(left, "left"), true, 0.5);
  cairo_restore(cr);
  cairo_save(cr);
  cairo_translate(cr, grid.page.width_mm - baseline, m + 0.5 * h);
  cairo_rotate(cr, 1.5707963267948966);
  show_text(cr, Vec2(0.0, 0.0), size, edge_text(right, "right"), true, 0.5);
  cairo_restore(cr);
}

/// Creates a PDF at a temporary name, lets `draw` fill it, checks cairo and commits.
template <typename Draw>
void write_pdf(const std::filesystem::path& path, double width_mm, double height_mm, Draw draw) {
  const auto tmp = temporary_path_for(path);
  try {
    {
      Surface surface(
          cairo_pdf_surface_create(tmp.c_str(), width_mm * kPointsPerMm, height_mm * kPointsPerMm),
          cairo_surface_destroy);
      Cairo cr(cairo_create(surface.get()), cairo_destroy);
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, "tightfit pattern");
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "tightfit");
      draw(cr.get());
      const cairo_status_t status = cairo_status(cr.get());
      cr.reset();
      cairo_surface_finish(surface.get());
      if (status != CAIRO_STATUS_SUCCESS ||
          cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        throw InputError(path.string(),
                         std::string("cannot write PDF: ") +
                             cairo_status_to_string(status != CAIRO_STATUS_SUCCESS
                                                        ? status
                                                        : cairo_surface_status(surface.get())));
      }
    }
    commit_temporary(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

}  // namespace

void write_pattern_pdf_tiled(const Pattern& pattern, const PatternExportOptions& options,
                             const std::filesystem::path& path) {
  const std::vector<PieceDrawing> pieces = draw_pattern_pieces(pattern, options, path.string());
  const PatternLayout layout = layout_pattern(pieces, options);
  const TileGrid grid = tile_grid(layout, options);
  write_pdf(path, grid.page.width_mm, grid.page.height_mm, [&](cairo_t* cr) {
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        cairo_save(cr);
        cairo_scale(cr, kPointsPerMm, kPointsPerMm);
        cairo_save(cr);
        cairo_rectangle(cr, grid.margin_mm, grid.margin_mm, grid.content_width_mm,
                        grid.content_height_mm);
        cairo_clip(cr);
        cairo_translate(cr, grid.margin_mm - c * grid.step_x_mm(),
                        grid.margin_mm - r * grid.step_y_mm());
        const Box2 view = tile_box(grid, r, c, kTileSlackMm);
        draw_layout(cr, pieces, layout, options, &view);
        draw_alignment_marks(cr, grid, view);
        cairo_restore(cr);
        draw_tile_furniture(cr, grid, r, c);
        cairo_restore(cr);
        cairo_show_page(cr);
      }
    }
  });
}

void write_pattern_pdf_full_size(const Pattern& pattern, const PatternExportOptions& options,
                                 const std::filesystem::path& path) {
  const std::vector<PieceDrawing> pieces = draw_pattern_pieces(pattern, options, path.string());
  const PatternLayout layout = layout_pattern(pieces, options);
  write_pdf(path, layout.width_mm, layout.height_mm, [&](cairo_t* cr) {
    cairo_scale(cr, kPointsPerMm, kPointsPerMm);
    draw_layout(cr, pieces, layout, options, nullptr);
    cairo_show_page(cr);
  });
}

}  // namespace tightfit
