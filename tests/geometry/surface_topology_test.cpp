#include "tightfit/geometry/surface_topology.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "test_meshes.hpp"

namespace tightfit::surface_topology_test {

TEST(SurfaceTopology, IcosahedronIsClosedManifold) {
  const TriMesh m = test::icosahedron();
  const SurfaceTopology topo(m.faces, m.num_vertices());
  EXPECT_EQ(topo.num_vertices(), 12);
  EXPECT_EQ(topo.num_faces(), 20);
  EXPECT_EQ(topo.num_edges(), 30);
  EXPECT_TRUE(topo.is_closed());
  EXPECT_TRUE(topo.boundary_loops().empty());
  EXPECT_TRUE(topo.non_manifold_edges().empty());
  EXPECT_TRUE(topo.non_manifold_vertices().empty());
  EXPECT_TRUE(topo.inconsistently_oriented_edges().empty());
  for (int v = 0; v < 12; ++v) {
    EXPECT_EQ(topo.vertex_faces(v).size(), 5u);
    EXPECT_EQ(topo.vertex_neighbors(v).size(), 5u);
  }
}

TEST(SurfaceTopology, FaceEdgesAndAcrossAreConsistent) {
  const TriMesh m = test::icosahedron();
  const SurfaceTopology topo(m.faces, m.num_vertices());
  for (int f = 0; f < topo.num_faces(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int e = topo.face_edge(f, i);
      const auto ev = topo.edge_vertices(e);
      const int a = m.faces(f, i), b = m.faces(f, (i + 1) % 3);
      EXPECT_EQ(ev[0], std::min(a, b));
      EXPECT_EQ(ev[1], std::max(a, b));
      const auto nb = topo.across(f, i);
      ASSERT_GE(nb.face, 0);
      ASSERT_NE(nb.face, f);
      EXPECT_EQ(topo.face_edge(nb.face, nb.edge_in_face), e);
      // The neighbour traverses the shared edge in the opposite direction.
      EXPECT_EQ(m.faces(nb.face, nb.edge_in_face), b);
      EXPECT_EQ(m.faces(nb.face, (nb.edge_in_face + 1) % 3), a);
      // Across is an involution.
      const auto back = topo.across(nb.face, nb.edge_in_face);
      EXPECT_EQ(back.face, f);
      EXPECT_EQ(back.edge_in_face, i);
      const auto ef = topo.edge_faces(e);
      EXPECT_TRUE((ef[0] == f && ef[1] == nb.face) || (ef[1] == f && ef[0] == nb.face));
      EXPECT_EQ(topo.find_edge(b, a), e);
    }
  }
  EXPECT_EQ(topo.find_edge(0, 3), -1);  // opposite vertices
}

TEST(SurfaceTopology, OpenStripHasOneBoundaryLoopFollowingOrientation) {
  const int n = 4;
  const TriMesh m = test::strip(n);
  const SurfaceTopology topo(m.faces, m.num_vertices());
  EXPECT_FALSE(topo.is_closed());
  EXPECT_EQ(topo.num_edges(), 4 * n + 1);  // 2n horizontal, n+1 vertical, n diagonal
  EXPECT_EQ(static_cast<int>(topo.boundary_edges().size()), 2 * n + 2);
  const auto loops = topo.boundary_loops();
  ASSERT_EQ(loops.size(), 1u);
  const auto& loop = loops[0];
  ASSERT_EQ(static_cast<int>(loop.size()), 2 * n + 2);
  EXPECT_EQ(std::set<int>(loop.begin(), loop.end()).size(), loop.size());
  // Counter-clockwise seen from +z: along the bottom row left to right, then back on top.
  for (size_t k = 0; k < loop.size(); ++k) {
    const int a = loop[k], b = loop[(k + 1) % loop.size()];
    const int e = topo.find_edge(a, b);
    ASSERT_GE(e, 0);
    EXPECT_TRUE(topo.is_boundary_edge(e));
    const Eigen::RowVector3d d = m.vertices.row(b) - m.vertices.row(a);
    const Eigen::RowVector3d mid = 0.5 * (m.vertices.row(a) + m.vertices.row(b));
    const Eigen::RowVector3d centre(n / 2.0, 0.5, 0.0);
    // (d x (centre - mid)) . z > 0: the interior lies to the left.
    EXPECT_GT(d.x() * (centre - mid).y() - d.y() * (centre - mid).x(), 0.0);
  }
  const int boundary_face = topo.edge_faces(topo.find_edge(0, 1))[0];
  EXPECT_EQ(topo.edge_faces(topo.find_edge(0, 1))[1], -1);
  int i0 = 0;
  while (topo.face_edge(boundary_face, i0) != topo.find_edge(0, 1)) ++i0;
  EXPECT_EQ(topo.across(boundary_face, i0).face, -1);
  EXPECT_EQ(topo.across(boundary_face, i0).edge_in_face, -1);
  EXPECT_TRUE(topo.non_manifold_vertices().empty());
}

TEST(SurfaceTopology, BowTieVertexIsNonManifold) {
  // Two triangles sharing only vertex 0.
  Triangles faces(2, 3);
  faces << 0, 1, 2, 0, 3, 4;
  const SurfaceTopology topo(faces, 5);
  EXPECT_EQ(topo.non_manifold_vertices(), std::vector<int>{0});
  EXPECT_TRUE(topo.non_manifold_edges().empty());
  const auto loops = topo.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(loops[1], (std::vector<int>{0, 3, 4}));
  EXPECT_EQ(topo.vertex_faces(0), (std::vector<int>{0, 1}));
  EXPECT_EQ(topo.vertex_neighbors(0), (std::vector<int>{1, 2, 3, 4}));
}

TEST(SurfaceTopology, NonManifoldEdgeHasNoUniqueNeighbour) {
  // Three triangles on edge (0,1).
  Triangles faces(3, 3);
  faces << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const SurfaceTopology topo(faces, 5);
  const int e = topo.find_edge(0, 1);
  EXPECT_EQ(topo.non_manifold_edges(), std::vector<int>{e});
  EXPECT_EQ(topo.edge_valence(e), 3);
  EXPECT_EQ(topo.edge_all_faces(e), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(topo.edge_faces(e), (std::array<int, 2>{0, 1}));
  EXPECT_EQ(topo.across(0, 0).face, -1);
  EXPECT_FALSE(topo.is_closed());
}

TEST(SurfaceTopology, DetectsInconsistentOrientation) {
  Triangles faces(2, 3);
  faces << 0, 1, 2, 0, 1, 3;  // both traverse 0 -> 1
  const SurfaceTopology topo(faces, 4);
  EXPECT_EQ(topo.inconsistently_oriented_edges(), std::vector<int>{topo.find_edge(0, 1)});
}

TEST(SurfaceTopology, DegenerateFaceDoesNotThrow) {
  Triangles faces(2, 3);
  faces << 0, 1, 1, 0, 1, 2;
  const SurfaceTopology topo(faces, 4);
  EXPECT_EQ(topo.isolated_vertices(), std::vector<int>{3});
  EXPECT_GE(topo.find_edge(1, 1), 0);
  EXPECT_NO_THROW(topo.boundary_loops());
  EXPECT_NO_THROW(topo.non_manifold_vertices());
}

TEST(SurfaceTopology, RejectsOutOfRangeIndex) {
  Triangles faces(1, 3);
  faces << 0, 1, 3;
  EXPECT_THROW(SurfaceTopology(faces, 3), std::invalid_argument);
  faces << 0, -1, 2;
  EXPECT_THROW(SurfaceTopology(faces, 3), std::invalid_argument);
}

}  // namespace tightfit::surface_topology_test
