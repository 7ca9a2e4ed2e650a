#include "tightfit/garment/piece_mesher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit::piece_mesher_test {

/// An L-shaped polygon (1 m × 1 m minus a 0.5 m corner) sampled every `h`.
Points2 l_shape(double h) {
  const std::vector<Vec2> corners{{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}};
  std::vector<Vec2> pts;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
    const int n = static_cast<int>(std::lround((b - a).norm() / h));
    for (int k = 0; k < n; ++k) pts.push_back(a + (b - a) * k / n);
  }
  Points2 p(static_cast<Eigen::Index>(pts.size()), 2);
  for (size_t i = 0; i < pts.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return p;
}

TEST(PieceMesher, KeepsTheBoundaryAndMakesGoodTriangles) {
  const double h = 0.05;
  const Points2 boundary = l_shape(h);
  const PieceMesh m = mesh_piece(boundary, h);
  const Eigen::Index nb = boundary.rows();
  EXPECT_TRUE(m.vertices.topRows(nb) == boundary);
  double area = 0.0, edge = 0.0;
  int edges = 0;
  for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
    const Vec2 a = m.vertices.row(m.triangles(f, 0)), b = m.vertices.row(m.triangles(f, 1)),
               c = m.vertices.row(m.triangles(f, 2));
    const double a2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    EXPECT_GT(a2, 0.0);
    area += 0.5 * a2;
    edge += (b - a).norm() + (c - b).norm() + (a - c).norm();
    edges += 3;
  }
  EXPECT_NEAR(area, 0.75, 1e-12);
  EXPECT_NEAR(edge / edges, h, 0.15 * h);
  EXPECT_GT(min_angle_deg(m.vertices, m.triangles), 25.0);
  // A disc whose boundary is exactly the input polygon, every vertex used.
  const SurfaceTopology topo(m.triangles, static_cast<int>(m.vertices.rows()));
  const auto loops = topo.boundary_loops();
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(static_cast<Eigen::Index>(loops[0].size()), nb);
  EXPECT_TRUE(topo.isolated_vertices().empty());
  EXPECT_TRUE(topo.non_manifold_vertices().empty());
}

TEST(PieceMesher, IsDeterministicAndRejectsBadBoundaries) {
  const Points2 boundary = l_shape(0.1);
  const PieceMesh a = mesh_piece(boundary, 0.1), b = mesh_piece(boundary, 0.1);
  EXPECT_TRUE(a.vertices == b.vertices);
  EXPECT_TRUE(a.triangles == b.triangles);
  EXPECT_THROW(mesh_piece(boundary.colwise().reverse(), 0.1), std::invalid_argument);  // clockwise
  Points2 bow(4, 2);
  bow << 0, 0, 1, 1, 1, 0, 0, 1;  // crosses itself
  EXPECT_THROW(mesh_piece(bow, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_piece(boundary.topRows(2), 0.1), std::invalid_argument);
}

}  // namespace tightfit::piece_mesher_test
