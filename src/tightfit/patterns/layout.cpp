#include "tightfit/patterns/layout.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace tightfit {
namespace {

Box2 piece_box(const PieceDrawing& piece) {
  Box2 box{piece.cut_line.front(), piece.cut_line.front()};
  auto grow = [&](const Vec2& q) {
    box.min = box.min.cwiseMin(q);
    box.max = box.max.cwiseMax(q);
  };
  for (const Vec2& q : piece.cut_line) grow(q);
  for (const Vec2& q : piece.sew_line) grow(q);
  for (const Notch& n : piece.notches) grow(n.cut);
  return box;
}

int tiles(double length, double content, double overlap) {
  if (length <= content) return 1;
  return static_cast<int>(std::ceil((length - overlap) / (content - overlap) - 1e-9));
}

}  // namespace

PatternLayout layout_pattern(const std::vector<PieceDrawing>& pieces,
                             const PatternExportOptions& options) {
  const double gap = options.layout_gap * kMmPerM;
  const double row_limit = options.layout_width * kMmPerM;
  PatternLayout layout;
  layout.offsets.resize(pieces.size());
  layout.piece_boxes.resize(pieces.size());
  double x = gap;
  double y = gap;
  double row_height = 0.0;
  double width = 0.0;
  // Places a w × h box; returns its top-left corner.
  auto place = [&](double w, double h) {
    if (x > gap && x + w > row_limit - gap) {
      y += row_height + gap;
      x = gap;
      row_height = 0.0;
    }
    const Vec2 corner(x, y);
    x += w + gap;
    row_height = std::max(row_height, h);
    width = std::max(width, x);
    return corner;
  };
  if (options.test_square) {
    const Vec2 corner = place(kTestSquareMm, kTestSquareMm);
    layout.has_test_square = true;
    layout.test_square = {corner, corner + Vec2(kTestSquareMm, kTestSquareMm)};
  }
  // One spot per piece, or per nest group (the union of its pieces' boxes).
  std::vector<int> group(pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p)
    group[p] = options.nest_group.empty() ? static_cast<int>(p) : options.nest_group[p];
  std::map<int, Box2> group_box;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const Box2 local = piece_box(pieces[p]);
    const auto [it, first] = group_box.emplace(group[p], local);
    if (!first)
      it->second = {it->second.min.cwiseMin(local.min), it->second.max.cwiseMax(local.max)};
  }
  std::map<int, Vec2> group_corner;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const Box2& local = group_box.at(group[p]);
    auto it = group_corner.find(group[p]);
    if (it == group_corner.end())
      it = group_corner.emplace(group[p], place(local.width(), local.height())).first;
    const Vec2 corner = it->second;
    layout.offsets[p] = Vec2(corner.x() - local.min.x(), corner.y() + local.max.y());
    layout.piece_boxes[p] = {corner, corner + Vec2(local.width(), local.height())};
  }
  layout.width_mm = width;
  layout.height_mm = y + row_height + gap;
  return layout;
}

TileGrid tile_grid(const PatternLayout& layout, const PatternExportOptions& options) {
  TileGrid grid;
  grid.page = paper_size(options.paper);
  grid.margin_mm = options.page_margin * 1000.0;
  grid.overlap_mm = options.tile_overlap * 1000.0;
  grid.content_width_mm = grid.page.width_mm - 2.0 * grid.margin_mm;
  grid.content_height_mm = grid.page.height_mm - 2.0 * grid.margin_mm;
  grid.cols = tiles(layout.width_mm, grid.content_width_mm, grid.overlap_mm);
  grid.rows = tiles(layout.height_mm, grid.content_height_mm, grid.overlap_mm);
  return grid;
}

Box2 tile_box(const TileGrid& grid, int row, int col, double slack_mm) {
  const Vec2 lo(col * grid.step_x_mm(), row * grid.step_y_mm());
  const Vec2 hi = lo + Vec2(grid.content_width_mm, grid.content_height_mm);
  return {lo.array() - slack_mm, hi.array() + slack_mm};
}

std::vector<OutlineRun> outline_runs(const std::vector<Vec2>& outline, const Box2& box) {
  std::vector<OutlineRun> runs;
  const size_t n = outline.size();
  double arc_length = 0.0;  // from vertex 0 to vertex i
  bool in_run = false;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = outline[i];
    const Vec2& b = outline[(i + 1) % n];
    if (box.meets(a.cwiseMin(b), a.cwiseMax(b))) {
      if (!in_run) runs.push_back({i, 0, arc_length});
      ++runs.back().count;
      in_run = true;
    } else {
      in_run = false;
    }
    arc_length += (b - a).norm();
  }
  return runs;
}

std::string tile_label(int row, int col) {
  std::string letters;
  for (int r = row + 1; r > 0; r = (r - 1) / 26) {
    letters.insert(letters.begin(), static_cast<char>('A' + (r - 1) % 26));
  }
  return letters + std::to_string(col + 1);
}

}  // namespace tightfit
