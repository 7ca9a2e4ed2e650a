/// The boundary plan of remeshing: units between break points, seam ranges, and the
/// guards against seams whose sides cannot be cut.
#include "tightfit/design/remesh_boundary.hpp"

#include <gtest/gtest.h>

#include "tightfit/common/error.hpp"

namespace tightfit::remesh_boundary_test {

/// Two unit squares (m) sewn along one side: piece 0's right side to piece 1's left.
Pattern two_squares() {
  Pattern pattern;
  for (int k = 0; k < 2; ++k) {
    PatternPiece piece;
    piece.name = "square " + std::to_string(k);
    piece.rest = (Points2(4, 2) << 0, 0, 1, 0, 1, 1, 0, 1).finished();
    piece.triangles = (Triangles(2, 3) << 0, 1, 2, 0, 2, 3).finished();
    piece.boundary = {0, 1, 2, 3};
    piece.corners = {0, 1, 2, 3};
    pattern.pieces.push_back(std::move(piece));
  }
  Seam seam;
  seam.name = "middle";
  seam.a = {0, {1, 2}};
  seam.b = {1, {0, 3}};
  pattern.seams.push_back(seam);
  return pattern;
}

TEST(RemeshBoundary, UnitsStartAtBreakPointsAndSeamsCoverTheirEdges) {
  const BoundaryPlan plan = plan_boundary(two_squares());
  ASSERT_EQ(plan.splits.size(), 1u);
  EXPECT_EQ(plan.splits[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(plan.unit_starts[0], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(plan.sides[0][0].dir, 1);
  EXPECT_EQ(plan.sides[0][1].dir, -1);
  EXPECT_EQ(plan.cover[0][1].seam, 0);
  EXPECT_EQ(plan.cover[0][1].side, 0);
  EXPECT_EQ(plan.cover[1][3].seam, 0);  // the edge 3 → 0 of piece 1
  EXPECT_EQ(plan.cover[1][3].side, 1);
  EXPECT_EQ(plan.cover[0][0].seam, -1);
}

TEST(RemeshBoundary, ASeamSideWithoutVerticesIsAnInputError) {
  // Without vertices a side has no ends to cut the loop at (and its split would be
  // empty): refused before any index arithmetic.
  for (const std::vector<int>& b : {std::vector<int>{}, std::vector<int>{0}}) {
    Pattern pattern = two_squares();
    pattern.seams[0].a.vertices.resize(b.size());
    pattern.seams[0].b.vertices = b;
    try {
      plan_boundary(pattern);
      ADD_FAILURE() << "a seam side of " << b.size() << " vertices was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("unequal or too few"), std::string::npos) << e.what();
    }
  }
}

}  // namespace tightfit::remesh_boundary_test
