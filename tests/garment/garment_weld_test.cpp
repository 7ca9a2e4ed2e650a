#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/garment/garment_topology.hpp"

namespace tightfit::garment_weld_test {

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

TEST(WeldTopology, AnExplicitVertexMapMustCoverEveryPatternVertexWithAGarmentVertex) {
  Pattern pattern;
  pattern.pieces = {square("left", 0), square("right", 2)};
  const GarmentTopology welded = weld_topology(pattern, {0, 1, 2, 3, 1, 4, 5, 2}, 6);
  EXPECT_EQ(welded.num_garment_vertices, 6);
  EXPECT_EQ(welded.garment_triangles(2, 0), 1);  // right piece's vertex 0 is garment vertex 1
  EXPECT_THROW(weld_topology(pattern, {0, 1, 2, 3, 1, 4, 5}, 6), InputError);
  EXPECT_THROW(weld_topology(pattern, {0, 1, 2, 3, 1, 4, 5, 6}, 6), InputError);
}

TEST(OnePieceTopology, WeldsTheRawArraysAndNamesItsSourceInEveryError) {
  Triangles triangles(2, 3);
  triangles << 0, 1, 2, 0, 2, 3;
  const GarmentTopology g =
      one_piece_topology("raw cloth", 4, triangles, {{{1, 2}}}, {0, 1, 2, 0}, 3);
  EXPECT_EQ(g.num_pattern_vertices(), 4);
  EXPECT_EQ(g.num_garment_vertices, 3);
  EXPECT_EQ(g.garment_triangles(1, 2), 0);
  EXPECT_EQ(g.triangle_piece, (std::vector<int>{0, 0}));
  EXPECT_EQ(g.seam_edges.size(), 1u);
  EXPECT_TRUE(g.pinned.empty());
  const auto message_of = [](auto&& build) {
    try {
      build();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string short_map = message_of([&] {
    one_piece_topology("raw cloth", 4, triangles, {}, {0, 1, 2}, 3);
  });
  EXPECT_NE(short_map.find("raw cloth"), std::string::npos) << short_map;
  EXPECT_NE(short_map.find("3 entries for 4 pattern vertices"), std::string::npos) << short_map;
  const std::string beyond = message_of([&] {
    one_piece_topology("raw cloth", 4, triangles, {}, {0, 1, 2, 3}, 3);
  });
  EXPECT_NE(beyond.find("pattern vertex 3 maps to garment vertex 3 outside [0, 3)"),
            std::string::npos)
      << beyond;
  Triangles bad = triangles;
  bad(1, 1) = 4;
  const std::string triangle = message_of([&] {
    one_piece_topology("raw cloth", 4, bad, {}, {0, 1, 2, 0}, 3);
  });
  EXPECT_NE(triangle.find("triangle 1 has pattern vertex 4 outside [0, 4)"), std::string::npos)
      << triangle;
  const std::string seam = message_of([&] {
    one_piece_topology("raw seams", 4, Triangles(0, 3), {{{2, -1}}}, {0, 1, 2, 0}, 3);
  });
  EXPECT_NE(seam.find("raw seams"), std::string::npos) << seam;
  EXPECT_NE(seam.find("seam edge 0 has pattern vertex -1"), std::string::npos) << seam;
}

TEST(WeldPattern, RefusesPiecesJoinedAlongTheSamePairOfSeamVerticesTwice) {
  // Two squares sewn along their corners 0, 1, 2: each square's triangle (0, 1, 2) has
  // only seam vertices, so both become the same garment triangle and the diagonal 0-2
  // carries four triangles.
  Pattern pattern;
  pattern.pieces = {square("front", 0), square("back", 2)};
  pattern.seams.push_back({"side", {0, {0, 1, 2}}, {1, {0, 1, 2}}});
  try {
    weld_pattern(pattern);
    FAIL() << "a doubled triangle was welded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("more than two triangles"), std::string::npos) << what;
    EXPECT_NE(what.find("back, front"), std::string::npos) << what;
  }
}

TEST(WeldPattern, RefusesASeamThatWeldsTwoCornersOfATriangle) {
  Pattern pattern;
  pattern.pieces = {square("only", 0)};
  pattern.seams.push_back({"fold", {0, {0, 1}}, {0, {1, 2}}});
  try {
    weld_pattern(pattern);
    FAIL() << "a triangle with two corners welded together was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("piece only"), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::garment_weld_test
