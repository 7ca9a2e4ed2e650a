/// Boundary resampling shared by the pattern builder and remeshing: cutting runs, edge
/// counts, arc-length location and sampling, and the guards of their index arithmetic.
#include "tightfit/garment/boundary_resampling.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tightfit::boundary_resampling_test {

TEST(BoundaryResampling, CutRunSplitsAtInteriorCutsOnly) {
  // Cuts at the run's ends (10 and 16) are not interior: only 12 and 15 split it.
  const std::vector<LoopRun> runs =
      cut_run({10, 6}, [](int p) { return p == 10 || p == 12 || p == 15 || p == 16; });
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].first, 10);
  EXPECT_EQ(runs[0].count, 2);
  EXPECT_EQ(runs[1].first, 12);
  EXPECT_EQ(runs[1].count, 3);
  EXPECT_EQ(runs[2].first, 15);
  EXPECT_EQ(runs[2].count, 1);
  const std::vector<LoopRun> whole = cut_run({3, 4}, [](int) { return false; });
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].first, 3);
  EXPECT_EQ(whole[0].count, 4);
}

TEST(BoundaryResampling, EdgeCountsKeepALoopOfThreeVerticesAndSeamSidesEqual) {
  EXPECT_EQ(min_edge_count(1), 3);
  EXPECT_EQ(min_edge_count(2), 2);
  EXPECT_EQ(min_edge_count(5), 1);
  EXPECT_EQ(edge_count(0.1, 0.02, 1), 5);
  EXPECT_EQ(edge_count(0.01, 0.02, 3), 3);
  EXPECT_EQ(seam_edge_count(0.1, 0.14, 0.02, 1, 1), 6);
  EXPECT_EQ(seam_edge_count(0.01, 0.01, 0.02, 1, 2), 2);
}

TEST(BoundaryResampling, LocateArcFindsTheEdgeAndParameter) {
  const std::vector<double> cum{0.0, 1.0, 1.0, 3.0};  // a zero-length middle edge
  const ArcPoint mid = locate_arc(cum, 0.5);
  EXPECT_EQ(mid.edge, 0);
  EXPECT_DOUBLE_EQ(mid.t, 0.5);
  const ArcPoint vertex = locate_arc(cum, 1.0);  // the last edge starting at the vertex
  EXPECT_EQ(vertex.edge, 2);
  EXPECT_EQ(vertex.t, 0.0);
  const ArcPoint late = locate_arc(cum, 2.0);
  EXPECT_EQ(late.edge, 2);
  EXPECT_DOUBLE_EQ(late.t, 0.5);
}

TEST(BoundaryResampling, SampleArcIsEvenInArcLength) {
  const Points2 points = (Points2(3, 2) << 0.0, 0.0, 1.0, 0.0, 1.0, 3.0).finished();
  const std::vector<double> cum = cumulative_lengths(points, {0, 1, 2});
  ASSERT_EQ(cum.size(), 3u);
  EXPECT_DOUBLE_EQ(cum.back(), 4.0);
  const std::vector<ArcPoint> s = sample_arc(cum, 4);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].edge, 0);
  EXPECT_EQ(s[0].t, 0.0);
  EXPECT_EQ(s[1].edge, 1);  // at the corner: the edge starting there
  EXPECT_EQ(s[1].t, 0.0);
  EXPECT_EQ(s[2].edge, 1);
  EXPECT_DOUBLE_EQ(s[2].t, 1.0 / 3.0);
  EXPECT_EQ(s[3].edge, 1);
  EXPECT_DOUBLE_EQ(s[3].t, 2.0 / 3.0);
}

TEST(BoundaryResampling, APolylineWithoutEdgesOrNoSamplesIsRefused) {
  // One sample (a single cumulative length) has no edge to locate on.
  EXPECT_THROW(locate_arc({0.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(locate_arc({}, 0.0), std::invalid_argument);
  EXPECT_THROW(sample_arc({0.0}, 3), std::invalid_argument);
  EXPECT_THROW(sample_arc({0.0, 1.0}, 0), std::invalid_argument);
}

TEST(BoundaryResampling, PolygonRowsKeepTheOrder) {
  const Points2 p = polygon_rows({Vec2(1, 2), Vec2(3, 4)});
  ASSERT_EQ(p.rows(), 2);
  EXPECT_EQ(p(1, 0), 3.0);
  EXPECT_EQ(p(0, 1), 2.0);
}

}  // namespace tightfit::boundary_resampling_test
