// The cut of a triangle mesh by a plane: loops, their closedness, the loop around a point
// and its length.
#include "tightfit/geometry/plane_loops.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace tightfit {
namespace plane_loops_test {

/// `columns` × `rows` vertices on a tube of radius `r` around the y axis (y from 0 to 1),
/// centred at x = `x0`; `closed`: the last column joins the first (a tube), else an open
/// strip of the same columns (a tube slit along one line).
TriMesh tube(double r, double x0, int columns, int rows, bool closed) {
  TriMesh m;
  m.vertices.resize(columns * rows, 3);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const double a = 2.0 * std::numbers::pi * i / columns;
      m.vertices.row(j * columns + i) << x0 + r * std::cos(a), static_cast<double>(j) / (rows - 1),
          r * std::sin(a);
    }
  const int across = closed ? columns : columns - 1;
  m.faces.resize(2 * across * (rows - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i < across; ++i) {
      const int a = j * columns + i, b = j * columns + (i + 1) % columns;
      m.faces.row(f++) << a, b, b + columns;
      m.faces.row(f++) << a, b + columns, a + columns;
    }
  return m;
}

/// Signed distances to the plane y = h.
std::vector<double> height_side(const TriMesh& m, double h) {
  std::vector<double> side;
  for (int v = 0; v < m.num_vertices(); ++v) side.push_back(m.vertices(v, 1) - h);
  return side;
}

/// Two meshes as one.
TriMesh join(const TriMesh& a, const TriMesh& b) {
  TriMesh m;
  m.vertices.resize(a.num_vertices() + b.num_vertices(), 3);
  m.vertices << a.vertices, b.vertices;
  m.faces.resize(a.num_faces() + b.num_faces(), 3);
  m.faces << a.faces, b.faces.array() + a.num_vertices();
  return m;
}

}  // namespace plane_loops_test

using namespace plane_loops_test;

TEST(PlaneCut, TwoTubesGiveTwoClosedLoopsAndTheOneAroundThePointIsPicked) {
  const int columns = 16;
  const TriMesh m = join(tube(0.1, 0.0, columns, 5, true), tube(0.05, 0.5, columns, 5, true));
  const PlaneCut cut = cut_by_plane(m, height_side(m, 0.4));
  ASSERT_EQ(cut.num_loops, 2);
  EXPECT_EQ(cut.closed, (std::vector<char>{1, 1}));
  // One segment per face between rows 1 and 2 (y 0.25, 0.5); a crossing 60 % up each
  // vertical edge.
  EXPECT_EQ(cut.segments.size(), 4u * columns);
  for (size_t i = 0; i < cut.edges.size(); ++i) {
    const Vec3 p = crossing_point(m, cut, static_cast<int>(i));
    EXPECT_NEAR(p.y(), 0.4, 1e-12);
  }
  const double polygon =
      2.0 * columns * std::sin(std::numbers::pi / columns);  // perimeter / radius
  for (const auto& [point, radius] :
       {std::pair{Vec3(0.0, 0.4, 0.0), 0.1}, std::pair{Vec3(0.5, 0.4, 0.0), 0.05}}) {
    const NearestCutLoop loop = nearest_cut_loop(m, cut, point, Vec3::UnitY());
    EXPECT_TRUE(loop.encloses);
    // Nearest: the crossings of the diagonal edges, 0.4 e_i + 0.6 e_(i+1) (chords).
    const double chord = std::sqrt(0.16 + 0.36 + 0.48 * std::cos(2.0 * std::numbers::pi / columns));
    EXPECT_NEAR(loop.distance, radius * chord, 1e-12);
    EXPECT_NEAR(cut_loop_length(m, cut, loop.loop), radius * polygon, 1e-12);
  }
  // A point beside both: no loop goes around it; the nearest one (the small tube) is picked.
  const NearestCutLoop beside = nearest_cut_loop(m, cut, Vec3(0.8, 0.4, 0.0), Vec3::UnitY());
  EXPECT_FALSE(beside.encloses);
  EXPECT_NEAR(cut_loop_length(m, cut, beside.loop), 0.05 * polygon, 1e-12);
}

TEST(PlaneCut, ASlitTubeGivesAnOpenLoopAndAMissedPlaneNone) {
  const TriMesh m = tube(0.1, 0.0, 16, 5, false);
  const PlaneCut cut = cut_by_plane(m, height_side(m, 0.4));
  ASSERT_EQ(cut.num_loops, 1);
  EXPECT_EQ(cut.closed, (std::vector<char>{0}));
  EXPECT_EQ(cut.segments.size(), 2u * 15u);
  const PlaneCut none = cut_by_plane(m, height_side(m, 1.5));
  EXPECT_EQ(none.num_loops, 0);
  EXPECT_TRUE(none.edges.empty());
  EXPECT_EQ(nearest_cut_loop(m, none, Vec3::Zero(), Vec3::UnitY()).loop, -1);
}

}  // namespace tightfit
