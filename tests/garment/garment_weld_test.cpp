#include <gtest/gtest.h>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/garment.hpp"

namespace tightfit {
namespace {

/// A unit square piece: 4 vertices, 2 triangles, boundary 0-1-2-3.
PatternPiece square(const std::string& name, double x0) {
  PatternPiece p;
  p.name = name;
  p.rest.resize(4, 2);
  p.rest << x0, 0, x0 + 1, 0, x0 + 1, 1, x0, 1;
  p.triangles.resize(2, 3);
  p.triangles << 0, 1, 2, 0, 2, 3;
  p.boundary = {0, 1, 2, 3};
  return p;
}

TEST(WeldPattern, SharesOneGarmentVertexPerSeamPair) {
  Pattern pattern;
  pattern.pieces = {square("left", 0), square("right", 2)};
  // Right edge of "left" (1→2) sewn to the left edge of "right" (0→3).
  pattern.seams.push_back({"side", {0, {1, 2}}, {1, {0, 3}}});
  pattern.pinned.push_back({"hem", 0, {0, 1}});
  const Garment g = weld_pattern(pattern);
  EXPECT_EQ(g.num_pattern_vertices(), 8);
  EXPECT_EQ(g.num_garment_vertices(), 6);
  EXPECT_EQ(g.topology->pattern_to_garment[1], g.topology->pattern_to_garment[4 + 0]);
  EXPECT_EQ(g.topology->pattern_to_garment[2], g.topology->pattern_to_garment[4 + 3]);
  EXPECT_EQ(g.topology->garment_triangles.rows(), 4);
  EXPECT_EQ(g.topology->seam_edges.size(), 2u);
  EXPECT_EQ(g.topology->pinned.size(), 2u);
  const Points2 rest = g.rest_positions();
  EXPECT_EQ(rest(5, 0), 3.0);
}

TEST(WeldPattern, RejectsSeamsWithUnequalSides) {
  Pattern pattern;
  pattern.pieces = {square("a", 0), square("b", 2)};
  pattern.seams.push_back({"bad", {0, {1, 2}}, {1, {0}}});
  EXPECT_THROW(weld_pattern(pattern), InputError);
  pattern.seams = {{"bad", {0, {1, 7}}, {1, {0, 3}}}};
  EXPECT_THROW(weld_pattern(pattern), InputError);
}

}  // namespace
}  // namespace tightfit
