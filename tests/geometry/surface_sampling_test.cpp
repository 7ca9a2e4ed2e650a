#include "tightfit/geometry/surface_sampling.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

#include "geometry/test_meshes.hpp"
#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit::surface_sampling_test {

TriMesh right_triangle() {
  TriMesh m;
  m.vertices.resize(3, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.faces.resize(1, 3);
  m.faces << 0, 1, 2;
  return m;
}

double nearest_distance(const Points3& points, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < points.rows(); ++k)
    best = std::min(best, (points.row(k).transpose() - x).norm());
  return best;
}

double smallest_pairwise_distance(const Points3& points) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < points.rows(); ++j)
      best = std::min(best, (points.row(i) - points.row(j)).norm());
  return best;
}

TEST(SurfaceSampling, AFineMeshGivesItsVertices) {
  const OrientedPoints s = sample_surface(right_triangle(), 2.0);
  ASSERT_EQ(s.points.rows(), 3);
  EXPECT_TRUE(s.points.isApprox(right_triangle().vertices));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR((s.normals.row(k) - Vec3(0, 0, 1).transpose()).norm(), 0.0, 1e-15);
}

TEST(SurfaceSampling, CountsAndCoversACoarseTriangle) {
  const TriMesh tri = right_triangle();
  const double spacing = 0.25;
  // Edges 1, 1, √2 → 4, 4, 6 parts; face level 6: 3 vertices + 3 + 3 + 5 edge points +
  // (6 − 1)(6 − 2)/2 = 10 inner points.
  EXPECT_EQ(count_surface_samples(tri, spacing), 24);
  const OrientedPoints s = sample_surface(tri, spacing);
  ASSERT_EQ(s.points.rows(), 24);
  for (Eigen::Index k = 0; k < s.points.rows(); ++k) {
    const Vec3 p = s.points.row(k).transpose();
    EXPECT_NEAR(p.z(), 0.0, 1e-15);
    EXPECT_GE(p.x(), -1e-15);
    EXPECT_GE(p.y(), -1e-15);
    EXPECT_LE(p.x() + p.y(), 1.0 + 1e-15);
    EXPECT_NEAR(s.normals.row(k).z(), 1.0, 1e-15);
  }
  // Every point of the triangle lies within one spacing of a sample.
  double worst = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; i + j <= 40; ++j)
      worst = std::max(worst, nearest_distance(s.points, Vec3(i / 40.0, j / 40.0, 0.0)));
  EXPECT_LE(worst, spacing);
  EXPECT_GT(smallest_pairwise_distance(s.points), 0.05);
}

TEST(SurfaceSampling, SharedEdgesAreSampledOnce) {
  const TriMesh strip = test::strip(3);  // unit squares, diagonals √2
  const OrientedPoints s = sample_surface(strip, 0.3);
  EXPECT_EQ(s.points.rows(), count_surface_samples(strip, 0.3));
  EXPECT_GT(smallest_pairwise_distance(s.points), 0.1);
}

TEST(SurfaceSampling, NormalsFollowTheVertexNormalsSmoothly) {
  const TriMesh ico = test::icosahedron();  // circumradius 1, edge 1.05
  const OrientedPoints s = sample_surface(ico, 0.2);
  const Points3 vn = vertex_normals(ico);
  ASSERT_GT(s.points.rows(), ico.num_vertices());
  for (int v = 0; v < ico.num_vertices(); ++v)
    EXPECT_LT((s.normals.row(v) - vn.row(v)).norm(), 1e-15);
  for (Eigen::Index k = 0; k < s.points.rows(); ++k) {
    EXPECT_NEAR(s.normals.row(k).norm(), 1.0, 1e-12);
    // Outward, and closer to the radial direction than the face normal (≈ 37° off at a
    // vertex) would be on average.
    const Vec3 radial = s.points.row(k).transpose().normalized();
    EXPECT_GT(s.normals.row(k).dot(radial.transpose()), 0.9);
  }
  // Neighbouring samples on either side of an edge have nearly the same normal.
  double worst_turn = 0.0;
  for (Eigen::Index i = 0; i < s.points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < s.points.rows(); ++j)
      if ((s.points.row(i) - s.points.row(j)).norm() < 0.2)
        worst_turn = std::max(worst_turn, (s.normals.row(i) - s.normals.row(j)).norm());
  EXPECT_LT(worst_turn, 0.3);  // face normals of neighbouring faces differ by 0.71
}

TEST(SurfaceSampling, PointsLieOnTheSmoothSurfaceNotOnTheFacets) {
  const TriMesh sphere = test::unit_icosphere();
  double flat_sag = 0.0;  // how far inside the sphere the facets' centroids lie
  for (int f = 0; f < sphere.num_faces(); ++f) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 3; ++k) c += sphere.vertices.row(sphere.faces(f, k)).transpose() / 3.0;
    flat_sag = std::max(flat_sag, 1.0 - c.norm());
  }
  const OrientedPoints s = sample_surface(sphere, 0.05);
  double worst = 0.0;
  for (Eigen::Index k = 0; k < s.points.rows(); ++k)
    worst = std::max(worst, std::abs(s.points.row(k).norm() - 1.0));
  std::printf("  facet centroids %.2e inside the sphere, samples within %.2e of it\n", flat_sag,
              worst);
  EXPECT_GT(flat_sag, 0.01);
  EXPECT_LT(worst, 0.2 * flat_sag);  // measured 0.14: the error left is of higher order
}

TEST(SurfaceSampling, SkipsDegenerateFacesAndUnusedVertices) {
  TriMesh m = right_triangle();
  m.vertices.conservativeResize(5, 3);
  m.vertices.row(3) << 2, 2, 2;  // unused
  m.vertices.row(4) << 3, 0, 0;  // only in a zero-area face
  m.faces.conservativeResize(2, 3);
  m.faces.row(1) << 0, 1, 4;  // collinear
  EXPECT_EQ(count_surface_samples(m, 10.0), 3);
  EXPECT_EQ(sample_surface(m, 10.0).points.rows(), 3);
  EXPECT_EQ(count_surface_samples(TriMesh{}, 1.0), 0);
}

TEST(SurfaceSampling, RefusesABadSpacing) {
  EXPECT_THROW(sample_surface(right_triangle(), 0.0), std::invalid_argument);
  EXPECT_THROW(count_surface_samples(right_triangle(), -1.0), std::invalid_argument);
  EXPECT_THROW(count_surface_samples(right_triangle(), std::nan("")), std::invalid_argument);
}

}  // namespace tightfit::surface_sampling_test
