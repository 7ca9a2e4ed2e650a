#include "tightfit/patterns/drawing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/layout.hpp"

namespace tightfit::pattern_drawing_test {

using test::inside_polygon;
using test::polygon_distance;

std::vector<const Notch*> notches_of(const PieceDrawing& piece, const std::string& seam, int side) {
  std::vector<const Notch*> out;
  for (const Notch& n : piece.notches) {
    if (n.seam == seam && n.side == side) out.push_back(&n);
  }
  return out;
}

TEST(PatternDrawing, SewLineIsTheBoundaryInMillimetres) {
  const Pattern pattern = test::test_pattern();
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  ASSERT_EQ(pieces.size(), 3u);
  for (size_t p = 0; p < pieces.size(); ++p) {
    const PatternPiece& piece = pattern.pieces[p];
    ASSERT_EQ(pieces[p].sew_line.size(), piece.boundary.size());
    for (size_t k = 0; k < piece.boundary.size(); ++k) {
      EXPECT_TRUE(
          pieces[p].sew_line[k].isApprox(piece.rest.row(piece.boundary[k]).transpose() * 1000.0));
    }
    EXPECT_EQ(pieces[p].quantity, 1);
  }
  EXPECT_NEAR(test::perimeter(pieces[0].sew_line), 1400.0, 1e-9);
}

TEST(PatternDrawing, PerSeamAllowanceAppliesToThatSeamsEdges) {
  PatternExportOptions options;
  options.seam_allowances["side_left"] = 0.015;
  options.seam_allowances["waist"] = 0.025;
  const auto pieces = draw_pattern_pieces(test::test_pattern(), options, "test");
  const PieceDrawing& front = pieces[0];
  // Front: bottom edges 0..5 are the pinned waist, left edges 20..27 the side_left seam.
  for (size_t k = 0; k < front.allowance.size(); ++k) {
    const double expected = k < 6 ? 25.0 : (k >= 20 ? 15.0 : 10.0);
    EXPECT_DOUBLE_EQ(front.allowance[k], expected) << k;
  }
  // The cut line is 25 mm below the waist, 15 mm left of the left side, 10 mm elsewhere.
  Vec2 lo = front.cut_line.front();
  Vec2 hi = lo;
  for (const Vec2& q : front.cut_line) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  EXPECT_NEAR(lo.x(), -15.0, 1e-9);
  EXPECT_NEAR(lo.y(), -25.0, 1e-9);
  EXPECT_NEAR(hi.x(), 310.0, 1e-9);
  EXPECT_NEAR(hi.y(), 410.0, 1e-9);
  // The back's right side is side_left's side a.
  for (size_t k = 6; k < 14; ++k) EXPECT_DOUBLE_EQ(pieces[1].allowance[k], 15.0);
}

TEST(PatternDrawing, NotchesMatchAcrossEachSeam) {
  const Pattern pattern = test::test_pattern();
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  // Seam lengths: 400 mm, ~401 mm (4 intervals of 10 cm) and 240 mm (2 intervals).
  const std::map<std::string, size_t> expected_count = {
      {"side_right", 5}, {"side_left", 5}, {"sleeve_hem", 3}};
  for (const Seam& seam : pattern.seams) {
    const auto a = notches_of(pieces[static_cast<size_t>(seam.a.piece)], seam.name, 0);
    const auto b = notches_of(pieces[static_cast<size_t>(seam.b.piece)], seam.name, 1);
    ASSERT_EQ(a.size(), expected_count.at(seam.name)) << seam.name;
    ASSERT_EQ(b.size(), a.size()) << seam.name;
    const PatternPiece& pa = pattern.pieces[static_cast<size_t>(seam.a.piece)];
    const PatternPiece& pb = pattern.pieces[static_cast<size_t>(seam.b.piece)];
    const Vec2 a0 = pa.rest.row(seam.a.vertices.front()).transpose() * 1000.0;
    const Vec2 a1 = pa.rest.row(seam.a.vertices.back()).transpose() * 1000.0;
    const Vec2 b0 = pb.rest.row(seam.b.vertices.front()).transpose() * 1000.0;
    const Vec2 b1 = pb.rest.row(seam.b.vertices.back()).transpose() * 1000.0;
    const double m = static_cast<double>(a.size() - 1);
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k]->index, static_cast<int>(k));
      EXPECT_EQ(b[k]->index, static_cast<int>(k));
      // The fixture's seam sides are straight and evenly divided: notch k sits at
      // arc-length fraction k/m on both sides, ends included.
      EXPECT_NEAR((a[k]->sew - (a0 + (a1 - a0) * (k / m))).norm(), 0.0, 1e-9) << seam.name << k;
      EXPECT_NEAR((b[k]->sew - (b0 + (b1 - b0) * (k / m))).norm(), 0.0, 1e-9) << seam.name << k;
    }
  }
}

// Notches are `notch_depth` deep (default 4 mm, the trade's 3–6 mm) and stop at the
// cut line where the allowance is smaller: depth = min(notch_depth, allowance). Before
// the notch depth existed, every notch ran to the cut line.
void check_notch_ticks(double notch_depth, double expected_default, double expected_side_left) {
  PatternExportOptions options;
  options.seam_allowances["side_left"] = 0.015;
  if (notch_depth >= 0.0) options.notch_depth = notch_depth;
  const Pattern pattern = test::test_pattern();
  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  size_t count = 0;
  for (const PieceDrawing& piece : pieces) {
    for (const Notch& n : piece.notches) {
      ++count;
      const double allowance = n.seam == "side_left" ? 15.0 : 10.0;
      const double expected = n.seam == "side_left" ? expected_side_left : expected_default;
      EXPECT_NEAR((n.cut - n.sew).norm(), expected, 1e-9);
      EXPECT_LT(polygon_distance(n.sew, piece.sew_line), 1e-9);
      EXPECT_LT(polygon_distance(n.sew, piece.trued_sew_line), 1e-9);
      const double to_cut = polygon_distance(n.cut, piece.cut_line);
      if (expected == allowance) {
        EXPECT_LT(to_cut, 1e-9) << piece.name << " " << n.seam;
      } else {
        // Inside the cut line, at most allowance − depth from it (less near corners).
        EXPECT_TRUE(inside_polygon(n.cut, piece.cut_line)) << piece.name << " " << n.seam;
        EXPECT_LE(to_cut, allowance - expected + 1e-6) << piece.name << " " << n.seam;
        EXPECT_GT(to_cut, 0.5) << piece.name << " " << n.seam;
      }
      EXPECT_FALSE(inside_polygon(n.cut, piece.sew_line));
      ASSERT_EQ(n.ticks.size(), 1u);
      EXPECT_EQ(n.ticks[0][0], n.sew);
      EXPECT_EQ(n.ticks[0][1], n.cut);
      // Perpendicular to a sew-line edge the notch sits on (at a corner, one of two).
      double best_dot = 1.0;
      for (size_t k = 0; k < piece.sew_line.size(); ++k) {
        const Vec2& s0 = piece.sew_line[k];
        const Vec2& s1 = piece.sew_line[(k + 1) % piece.sew_line.size()];
        if (test::segment_distance(n.sew, s0, s1) > 1e-9) continue;
        best_dot =
            std::min(best_dot, std::abs((s1 - s0).normalized().dot((n.cut - n.sew).normalized())));
      }
      EXPECT_NEAR(best_dot, 0.0, 1e-9);
    }
  }
  EXPECT_EQ(count, 2u * (5 + 5 + 3));
}

TEST(PatternDrawing, NotchesArePerpendicularTicksFromSewToCutLine) {
  // Deeper than every allowance: the notches reach the cut line.
  check_notch_ticks(0.020, 10.0, 15.0);
}

TEST(PatternDrawing, NotchDepthDefaultsToFourMillimetres) { check_notch_ticks(-1.0, 4.0, 4.0); }

TEST(PatternDrawing, NotchDepthClampedToTheAllowanceOfItsEdge) {
  // 12 mm: within the 15 mm side_left allowance, beyond the 10 mm of the others.
  check_notch_ticks(0.012, 10.0, 12.0);
}

TEST(PatternDrawing, NotchParametersFollowTheVertexCorrespondence) {
  // Side a evenly divided, side b with its middle vertex off-centre: notches sit at the
  // mean normalised arc length, at the same segment and parameter on both sides.
  const std::vector<Vec2> a = {{0, 0}, {100, 0}, {200, 0}};
  const std::vector<Vec2> b = {{0, 0}, {50, 0}, {200, 0}};
  const SeamNotchParameters p = seam_notch_parameters(a, b, 100.0);
  ASSERT_EQ(p.t.size(), 3u);
  EXPECT_EQ(p.segment.front(), 0);
  EXPECT_DOUBLE_EQ(p.t.front(), 0.0);
  EXPECT_EQ(p.segment.back(), 1);
  EXPECT_DOUBLE_EQ(p.t.back(), 1.0);
  // Vertex 1 is at fractions 0.5 and 0.25 → mean 0.375; fraction 0.5 lies in segment 1 at
  // (0.5 − 0.375) / (1 − 0.375) = 0.2.
  EXPECT_EQ(p.segment[1], 1);
  EXPECT_NEAR(p.t[1], 0.2, 1e-12);
  EXPECT_EQ(seam_notch_parameters(a, b, 0.0).t.size(), 2u);
}

TEST(PatternDrawing, GrainLineThroughCentroidAlongGrain) {
  const Pattern pattern = test::test_pattern();
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  for (size_t p = 0; p < pieces.size(); ++p) {
    const PieceDrawing& d = pieces[p];
    EXPECT_NEAR((0.5 * (d.grain_start + d.grain_end) - d.centroid).norm(), 0.0, 1e-9);
    const Vec2 dir = (d.grain_end - d.grain_start).normalized();
    EXPECT_NEAR(dir.dot(pattern.pieces[p].grain.normalized()), 1.0, 1e-12);
    EXPECT_GT((d.grain_end - d.grain_start).norm(), 100.0);
    EXPECT_TRUE(inside_polygon(d.grain_start, d.sew_line));
    EXPECT_TRUE(inside_polygon(d.grain_end, d.sew_line));
  }
  EXPECT_NEAR((pieces[0].centroid - Vec2(150, 200)).norm(), 0.0, 1e-9);
}

TEST(PatternDrawing, LayoutDoesNotOverlapAndContainsEverything) {
  PatternExportOptions options;
  options.layout_width = 0.5;
  const auto pieces = draw_pattern_pieces(test::test_pattern(), options, "test");
  const PatternLayout layout = layout_pattern(pieces, options);
  std::vector<Box2> boxes = layout.piece_boxes;
  ASSERT_TRUE(layout.has_test_square);
  EXPECT_NEAR(layout.test_square.width(), 100.0, 1e-12);
  boxes.push_back(layout.test_square);
  for (size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_GE(boxes[i].min.x(), 0.0);
    EXPECT_GE(boxes[i].min.y(), 0.0);
    EXPECT_LE(boxes[i].max.x(), layout.width_mm);
    EXPECT_LE(boxes[i].max.y(), layout.height_mm);
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const bool apart =
          boxes[i].max.x() <= boxes[j].min.x() || boxes[j].max.x() <= boxes[i].min.x() ||
          boxes[i].max.y() <= boxes[j].min.y() || boxes[j].max.y() <= boxes[i].min.y();
      EXPECT_TRUE(apart) << i << " " << j;
    }
  }
  for (size_t p = 0; p < pieces.size(); ++p) {
    for (const Vec2& q : pieces[p].cut_line) {
      const Vec2 l = layout.to_layout(p, q);
      EXPECT_GE(l.x(), layout.piece_boxes[p].min.x() - 1e-9);
      EXPECT_LE(l.x(), layout.piece_boxes[p].max.x() + 1e-9);
      EXPECT_GE(l.y(), layout.piece_boxes[p].min.y() - 1e-9);
      EXPECT_LE(l.y(), layout.piece_boxes[p].max.y() + 1e-9);
    }
  }
  // y flips: the front's top edge (y = 400 mm) is above its bottom edge on the paper.
  EXPECT_LT(layout.to_layout(0, {0, 400}).y(), layout.to_layout(0, {0, 0}).y());
}

TEST(PatternDrawing, TileGridAndLabels) {
  EXPECT_EQ(tile_label(0, 0), "A1");
  EXPECT_EQ(tile_label(1, 1), "B2");
  EXPECT_EQ(tile_label(25, 9), "Z10");
  EXPECT_EQ(tile_label(26, 0), "AA1");
  PatternLayout layout;
  layout.width_mm = 186.0;  // exactly one A4 content width (210 − 2 × 12)
  layout.height_mm = 273.0 + 263.0 + 1.0;
  const TileGrid grid = tile_grid(layout, {});
  EXPECT_EQ(grid.cols, 1);
  EXPECT_EQ(grid.rows, 3);
  EXPECT_DOUBLE_EQ(grid.step_y_mm(), 263.0);
}

TEST(PatternDrawing, TileBoxIsTheContentRectangleAtTheTilesPlace) {
  PatternLayout layout;
  layout.width_mm = 500.0;
  layout.height_mm = 600.0;
  const TileGrid grid = tile_grid(layout, {});
  const Box2 box = tile_box(grid, 1, 2, 0.5);
  EXPECT_DOUBLE_EQ(box.min.x(), 2.0 * grid.step_x_mm() - 0.5);
  EXPECT_DOUBLE_EQ(box.min.y(), grid.step_y_mm() - 0.5);
  EXPECT_DOUBLE_EQ(box.width(), grid.content_width_mm + 1.0);
  EXPECT_DOUBLE_EQ(box.height(), grid.content_height_mm + 1.0);
}

TEST(PatternDrawing, OutlineRunsKeepTheEdgesABoxMeetsWithTheirArcLength) {
  // A 40 mm × 20 mm outline, vertex 0 at the origin, 10 mm edges, counter-clockwise.
  std::vector<Vec2> outline;
  for (double x = 0.0; x < 40.0; x += 10.0) outline.emplace_back(x, 0.0);
  for (double y = 0.0; y < 20.0; y += 10.0) outline.emplace_back(40.0, y);
  for (double x = 40.0; x > 0.0; x -= 10.0) outline.emplace_back(x, 20.0);
  for (double y = 20.0; y > 0.0; y -= 10.0) outline.emplace_back(0.0, y);
  ASSERT_EQ(outline.size(), 12u);

  const auto all = outline_runs(outline, {{-1.0, -1.0}, {41.0, 21.0}});
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].first, 0u);
  EXPECT_EQ(all[0].count, 12u);
  EXPECT_DOUBLE_EQ(all[0].arc_length, 0.0);

  EXPECT_TRUE(outline_runs(outline, {{100.0, 100.0}, {110.0, 110.0}}).empty());

  // A box over the right end: edge 3 (x 30 … 40 at the bottom), 4 and 5 (the right
  // side), 6 (x 40 … 30 at the top).
  const auto right = outline_runs(outline, {{35.0, -5.0}, {45.0, 25.0}});
  ASSERT_EQ(right.size(), 1u);
  EXPECT_EQ(right[0].first, 3u);
  EXPECT_EQ(right[0].count, 4u);
  EXPECT_DOUBLE_EQ(right[0].arc_length, 30.0);

  // A box over the left side meets the last edges and the first one: two runs, the
  // second one starting at vertex 0 (a run does not wrap past it).
  const auto left = outline_runs(outline, {{-5.0, -5.0}, {5.0, 25.0}});
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0].first, 0u);
  EXPECT_EQ(left[0].count, 1u);
  EXPECT_DOUBLE_EQ(left[0].arc_length, 0.0);
  EXPECT_EQ(left[1].first, 9u);
  EXPECT_EQ(left[1].count, 3u);
  EXPECT_DOUBLE_EQ(left[1].arc_length, 90.0);
}

void expect_input_error(const Pattern& pattern, const std::string& fragment,
                        const PatternExportOptions& options = {}) {
  try {
    draw_pattern_pieces(pattern, options, "out/pattern.svg");
    ADD_FAILURE() << "expected InputError containing '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out/pattern.svg"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(PatternDrawing, InvalidPatternsAreInputErrors) {
  {
    Pattern p = test::test_pattern();
    p.pieces[1].rest.resize(0, 2);
    p.pieces[1].triangles.resize(0, 3);
    p.pieces[1].boundary.clear();
    expect_input_error(p, "empty piece");
  }
  {
    Pattern p = test::test_pattern();
    p.seams[0].b.vertices.pop_back();
    expect_input_error(p, "different vertex counts");
  }
  {
    Pattern p = test::test_pattern();
    p.pieces[0].triangles(3, 1) = 999;
    expect_input_error(p, "out of range");
  }
  {
    Pattern p = test::test_pattern();
    p.seams[2].a.vertices[3] = 99;
    expect_input_error(p, "out of range");
  }
  {
    Pattern p = test::test_pattern();
    p.seams[1].b.piece = 7;
    expect_input_error(p, "piece index 7 out of range");
  }
  {
    Pattern p = test::test_pattern();
    p.pinned[0].vertices = {0, 2, 3};
    expect_input_error(p, "not consecutive");
  }
  {
    Pattern p = test::test_pattern();
    std::reverse(p.pieces[2].boundary.begin(), p.pieces[2].boundary.end());
    expect_input_error(p, "not counter-clockwise");
  }
  {
    Pattern p = test::test_pattern();
    p.pieces[2].name = "front";
    expect_input_error(p, "duplicate piece name");
  }
  {
    PatternExportOptions options;
    options.seam_allowances["no_such_seam"] = 0.01;
    expect_input_error(test::test_pattern(), "unknown seam 'no_such_seam'", options);
  }
  expect_input_error(Pattern{}, "no pieces");
}

}  // namespace tightfit::pattern_drawing_test
