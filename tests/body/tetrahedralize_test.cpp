#include "tightfit/body/tetrahedralize.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

#include "tightfit/body/generators.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit::tetrahedralize_test {

TriMesh small_sphere() {
  SphereParams p;
  p.radius = 0.05;
  p.edge_length = 0.02;
  return sphere_surface(p);
}

std::set<std::array<int, 3>> boundary_faces(const TetMesh& mesh) {
  std::map<std::array<int, 3>, int> count;
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      int k = 0;
      for (int c = 0; c < 4; ++c)
        if (c != skip) f[k++] = mesh.tets(t, c);
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  std::set<std::array<int, 3>> out;
  for (const auto& [f, n] : count)
    if (n == 1) out.insert(f);
  return out;
}

TEST(Tetrahedralize, KeepsTheSurfaceAsTheFirstVerticesAndAsTheBoundary) {
  const TriMesh surface = small_sphere();
  TetQuality q;
  q.max_volume = regular_tet_volume(0.02);
  const TetMesh mesh = tetrahedralize_surface(surface, q);
  ASSERT_GT(mesh.num_vertices(), surface.num_vertices());  // interior Steiner points
  EXPECT_EQ(mesh.vertices.topRows(surface.num_vertices()), surface.vertices);
  std::set<std::array<int, 3>> expected;
  for (int f = 0; f < surface.num_faces(); ++f) {
    std::array<int, 3> s{surface.faces(f, 0), surface.faces(f, 1), surface.faces(f, 2)};
    std::sort(s.begin(), s.end());
    expected.insert(s);
  }
  EXPECT_EQ(boundary_faces(mesh), expected);
  EXPECT_TRUE(tet_mesh_problems(mesh).empty());  // positive orientation, no flat tets
  EXPECT_NEAR(total_volume(mesh), signed_volume(surface), 1e-12);
  // TetGen cannot split tets whose circumcentre lies outside without touching the
  // boundary (-Y), so the bound is not strict; a tighter bound still gives more tets.
  q.max_volume /= 8.0;
  EXPECT_GT(tetrahedralize_surface(surface, q).num_tets(), 2 * mesh.num_tets());
}

TEST(Tetrahedralize, InteriorPointsFollowTheSurfaceVertices) {
  const TriMesh surface = small_sphere();
  Points3 interior(3, 3);
  interior << 0, 0, 0, 0.01, 0, 0, 0, 0.02, 0.005;
  const TetMesh mesh = tetrahedralize_surface(surface, TetQuality(), interior);
  EXPECT_EQ(mesh.vertices.topRows(surface.num_vertices()), surface.vertices);
  EXPECT_EQ(mesh.vertices.middleRows(surface.num_vertices(), 3), interior);
}

TEST(Tetrahedralize, InternalSurfaceBecomesInteriorFaces) {
  const TriMesh surface = small_sphere();
  SphereParams inner;
  inner.radius = 0.025;
  inner.edge_length = 0.01;
  inner.fit_limit = false;
  const TriMesh core = sphere_surface(inner);
  Points3 interior(1, 3);
  interior << 0.0, 0.0, 0.04;  // between the two surfaces
  const TetMesh mesh = tetrahedralize_surface(surface, TetQuality(), interior, core);
  const int n = surface.num_vertices();
  EXPECT_EQ(mesh.vertices.topRows(n), surface.vertices);
  EXPECT_EQ(mesh.vertices.middleRows(n, core.num_vertices()), core.vertices);
  EXPECT_EQ(mesh.vertices.row(n + core.num_vertices()), interior.row(0));
  EXPECT_TRUE(tet_mesh_problems(mesh).empty());
  // Every core triangle is a face of two tets: one inside the core, one outside.
  std::map<std::array<int, 3>, int> count;
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      int k = 0;
      for (int c = 0; c < 4; ++c)
        if (c != skip) f[k++] = mesh.tets(t, c);
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  for (int f = 0; f < core.num_faces(); ++f) {
    std::array<int, 3> face{core.faces(f, 0) + n, core.faces(f, 1) + n, core.faces(f, 2) + n};
    std::sort(face.begin(), face.end());
    EXPECT_EQ(count[face], 2) << f;
  }
}

TEST(Tetrahedralize, QualityBoundsAreChecked) {
  TetQuality q;
  q.max_radius_edge = 0.9;
  EXPECT_THROW(tetgen_switches(q), std::invalid_argument);
  q = TetQuality();
  q.min_dihedral_deg = 25.0;
  EXPECT_THROW(tetgen_switches(q), std::invalid_argument);
  q = TetQuality();
  q.max_volume = 1e-6;
  EXPECT_EQ(tetgen_switches(q), "pYMq1.4/12a1.000000e-06zQ");
}

TEST(Tetrahedralize, SelfIntersectingSurfaceIsAnInputError) {
  // Two overlapping spheres in one mesh.
  const TriMesh a = small_sphere();
  TriMesh both;
  both.vertices.resize(2 * a.num_vertices(), 3);
  both.vertices << a.vertices, (a.vertices.rowwise() + Eigen::RowVector3d(0.03, 0, 0));
  both.faces.resize(2 * a.num_faces(), 3);
  both.faces << a.faces, (a.faces.array() + a.num_vertices()).matrix();
  EXPECT_THROW(tetrahedralize_surface(both, TetQuality()), InputError);
}

TEST(Tetrahedralize, TheTetCountIsBudgetedBeforeTetGenRuns) {
  // A ball of 0.5 m radius with tetrahedra of at most a regular one of 2 cm edges: at
  // least 0.53 m³ / 9.4e-7 m³ = 564 000 tetrahedra. Refused at once, naming the lengths.
  SphereParams p;
  p.radius = 0.5;
  p.edge_length = 0.1;
  const TriMesh ball = sphere_surface(p);
  TetQuality q;
  q.max_volume = regular_tet_volume(0.02);
  try {
    tetrahedralize_surface(ball, q);
    ADD_FAILURE() << "meshed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("would be meshed into at least 5.6"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("interior_edge_length"), std::string::npos) << e.what();
  }
  q.max_volume = regular_tet_volume(0.2);  // 555 times fewer: meshed
  EXPECT_GT(tetrahedralize_surface(ball, q).num_tets(), 0);
}

TEST(Tetrahedralize, ConstraintsOutsideTheSurfaceAreInputErrors) {
  const TriMesh surface = small_sphere();
  Points3 outside(1, 3);
  outside << 0.2, 0.0, 0.0;
  EXPECT_THROW(tetrahedralize_surface(surface, TetQuality(), outside), InputError);
  TriMesh shifted = surface;  // crosses the surface
  shifted.vertices.col(0).array() += 0.03;
  EXPECT_THROW(tetrahedralize_surface(surface, TetQuality(), Points3(0, 3), shifted), InputError);
}

}  // namespace tightfit::tetrahedralize_test
