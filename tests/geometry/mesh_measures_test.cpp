#include "tightfit/geometry/mesh_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_meshes.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::mesh_measures_test {

TEST(MeshMeasures, TriangleAndFaceAreas) {
  EXPECT_DOUBLE_EQ(triangle_area(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0)), 3.0);
  EXPECT_DOUBLE_EQ(triangle_area(Vec3(0, 0, 0), Vec3(0, 3, 0), Vec3(2, 0, 0)), 3.0);
  EXPECT_DOUBLE_EQ(triangle_area(Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)), 0.0);
  const TriMesh m = test::cube();
  const VecX areas = face_areas(m);
  for (int f = 0; f < m.num_faces(); ++f) EXPECT_EQ(face_area(m, f), areas[f]);
}

TEST(MeshMeasures, CubeVolumeAreaNormalsBox) {
  TriMesh m = test::cube();
  m.vertices *= 2.0;
  EXPECT_NEAR(signed_volume(m), 8.0, 1e-14);
  EXPECT_NEAR(surface_area(m), 24.0, 1e-14);
  EXPECT_NEAR(face_areas(m).minCoeff(), 2.0, 1e-14);
  const Points3 n = face_normals(m);
  EXPECT_EQ(n.row(0), Eigen::RowVector3d(0, 0, -1));
  EXPECT_EQ(n.row(11), Eigen::RowVector3d(1, 0, 0));
  // Translation does not change the volume of a closed surface.
  m.vertices.rowwise() += Eigen::RowVector3d(5, -3, 2);
  EXPECT_NEAR(signed_volume(m), 8.0, 1e-12);
  // Reversed faces give the negative volume.
  m.faces.col(1).swap(m.faces.col(2));
  EXPECT_NEAR(signed_volume(m), -8.0, 1e-12);
}

TEST(MeshMeasures, IcosahedronVertexNormalsPointOutward) {
  const TriMesh m = test::icosahedron();
  const Points3 n = vertex_normals(m);
  for (int i = 0; i < m.num_vertices(); ++i)
    EXPECT_NEAR(n.row(i).dot(m.vertices.row(i)), 1.0, 1e-12);
  // Icosahedron with circumradius 1: edge a = 4 / sqrt(10 + 2 sqrt 5).
  const double a = 4.0 / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
  const EdgeLengthStats s = edge_length_stats(m);
  EXPECT_EQ(s.count, 30);
  EXPECT_NEAR(s.min, a, 1e-12);
  EXPECT_NEAR(s.max, a, 1e-12);
  EXPECT_NEAR(s.median, a, 1e-12);
  EXPECT_NEAR(signed_volume(m), 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * a * a * a, 1e-12);
}

TEST(MeshMeasures, EdgeStatsOfStrip) {
  const EdgeLengthStats s = edge_length_stats(test::strip(2));
  // 4 horizontal and 3 vertical unit edges, 2 diagonals of sqrt 2.
  EXPECT_EQ(s.count, 9);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_NEAR(s.max, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(s.mean, (7.0 + 2.0 * std::sqrt(2.0)) / 9.0, 1e-15);
  EXPECT_EQ(s.median, 1.0);
}

TEST(MeshMeasures, RegularTetAnglesAndRadiusEdgeRatio) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  const double vol = tet_volume(a, b, c, d);
  EXPECT_NEAR(std::abs(vol), 8.0 / 3.0, 1e-14);
  const double expected = std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi;  // 70.53°
  for (double angle : tet_dihedral_angles(a, b, c, d)) EXPECT_NEAR(angle, expected, 1e-12);
  EXPECT_NEAR(tet_radius_edge_ratio(a, b, c, d), std::sqrt(6.0) / 4.0, 1e-14);
  EXPECT_TRUE(std::isinf(tet_radius_edge_ratio(a, b, c, a)));
}

TEST(MeshMeasures, CornerTetAndMeshSummaries) {
  TetMesh m;
  m.vertices.resize(5, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  m.tets.resize(2, 4);
  m.tets << 0, 1, 2, 3, 1, 4, 2, 3;
  const VecX vols = tet_volumes(m);
  EXPECT_NEAR(vols[0], 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(vols[1], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(total_volume(m), 0.5, 1e-15);
  // Corner tet: 90° at the three edges through the origin, acos(1/sqrt 3) = 54.7° at the others.
  const auto angles = tet_dihedral_angles(m.vertices.row(0), m.vertices.row(1), m.vertices.row(2),
                                          m.vertices.row(3));
  for (int e = 0; e < 3; ++e) EXPECT_NEAR(angles[e], 90.0, 1e-12);
  for (int e = 3; e < 6; ++e)
    EXPECT_NEAR(angles[e], std::acos(1.0 / std::sqrt(3.0)) * 180 / std::numbers::pi, 1e-12);
  const AngleRange range = dihedral_angle_range(m);
  EXPECT_NEAR(range.max_degrees, 90.0, 1e-12);
  EXPECT_LT(range.min_degrees, 54.8);
  // Corner tet: circumcentre (1/2,1/2,1/2), radius sqrt(3)/2, shortest edge 1.
  EXPECT_NEAR(radius_edge_ratios(m)[0], std::sqrt(3.0) / 2.0, 1e-14);
  EXPECT_GE(radius_edge_ratios(m).maxCoeff(), std::sqrt(3.0) / 2.0);
  EXPECT_EQ(edge_length_stats(m).count, 9);
}

TEST(MeshMeasures, LegsBodyIsOutward) {
  const TriMesh m = read_tri_mesh(TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj");
  EXPECT_GT(signed_volume(m), 0.0);
  EXPECT_GT(edge_length_stats(m).min, 0.0);
}

}  // namespace tightfit::mesh_measures_test
