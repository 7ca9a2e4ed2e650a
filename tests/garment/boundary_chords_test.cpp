#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "tightfit/garment/boundary_chords.hpp"
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit::boundary_chords_test {

double signed_area(const PieceMesh& m, Eigen::Index t) {
  const Vec2 a = m.vertices.row(m.triangles(t, 0)).transpose();
  const Vec2 b = m.vertices.row(m.triangles(t, 1)).transpose();
  const Vec2 c = m.vertices.row(m.triangles(t, 2)).transpose();
  const Vec2 u = b - a, v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

/// Interior edges (two triangles) whose two ends are both below `num_boundary`.
int count_chords(const PieceMesh& m, int num_boundary) {
  std::map<std::pair<int, int>, int> count;
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles(t, k), b = m.triangles(t, (k + 1) % 3);
      if (a < num_boundary && b < num_boundary) ++count[std::minmax(a, b)];
    }
  int chords = 0;
  for (const auto& [edge, n] : count) chords += n == 2 ? 1 : 0;
  return chords;
}

TEST(BoundaryChords, SplitsEveryChordKeepingAreaAndOrientation) {
  // A fan of a pentagon: the chords 0-2 and 0-3 join boundary vertices.
  PieceMesh mesh;
  mesh.vertices.resize(5, 2);
  mesh.vertices << 0, 0, 2, 0, 3, 1.5, 1, 3, -1, 1.5;
  mesh.triangles.resize(3, 3);
  mesh.triangles << 0, 1, 2, 0, 2, 3, 0, 3, 4;
  double area = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) area += signed_area(mesh, t);
  ASSERT_EQ(count_chords(mesh, 5), 2);

  EXPECT_EQ(split_boundary_chords(mesh, 5), 2);
  EXPECT_EQ(mesh.vertices.rows(), 7);
  EXPECT_EQ(mesh.triangles.rows(), 7);
  EXPECT_EQ(count_chords(mesh, 5), 0);
  double after = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    EXPECT_GT(signed_area(mesh, t), 0.0) << "triangle " << t;
    after += signed_area(mesh, t);
  }
  EXPECT_NEAR(after, area, 1e-12);
  EXPECT_TRUE(mesh.vertices.row(5).isApprox(Eigen::RowVector2d(1.5, 0.75)));
}

TEST(BoundaryChords, TheMesherLeavesNoChordInAThinPiece) {
  // A long sliver 6 edge lengths long and a third of one wide: no lattice point fits
  // inside, so the triangulation joins boundary vertices only until the chords are split.
  const double h = 0.01;
  Points2 boundary(14, 2);
  for (int i = 0; i <= 6; ++i) boundary.row(i) << i * h, 0.0;
  for (int i = 0; i <= 6; ++i) boundary.row(7 + i) << (6 - i) * h, h / 3.0;
  const PieceMesh mesh = mesh_piece(boundary, h);
  EXPECT_EQ(count_chords(mesh, 14), 0);
  EXPECT_GT(mesh.vertices.rows(), 14);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) EXPECT_GT(signed_area(mesh, t), 0.0);
}

}  // namespace tightfit::boundary_chords_test
