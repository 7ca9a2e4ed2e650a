#include "tightfit/garment/flatten.hpp"

#include <gtest/gtest.h>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit::flatten_test {

/// Half of a developable cylinder (a disc): faces with centroid x > 0... built directly.
TriMesh half_cylinder(double radius, double length, int segments, int rings) {
  TriMesh m;
  m.vertices.resize((segments + 1) * rings, 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double a = test::kPi * s / segments;
      m.vertices.row(r * (segments + 1) + s) << radius * std::cos(a), length * r / (rings - 1),
          -radius * std::sin(a);
    }
  m.faces.resize(2 * segments * (rings - 1), 3);
  int f = 0;
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * (segments + 1) + s, b = a + 1, c = a + segments + 1, d = b + segments + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  return m;
}

std::vector<int> boundary_of(const TriMesh& m) {
  const SurfaceTopology topo(m.faces, m.num_vertices());
  return topo.boundary_loops().at(0);
}

TEST(Flatten, DevelopableHalfCylinderIsIsometric) {
  const TriMesh m = half_cylinder(0.05, 0.3, 16, 20);
  const Flattening flat = flatten_panel(m, {boundary_of(m)});
  EXPECT_EQ(flat.report.flipped, 0);
  EXPECT_LT(flat.report.area_error, 1e-6);
  EXPECT_LT(flat.report.max_area_distortion, 1e-5);
  EXPECT_LT(flat.report.max_angle_error_deg, 1e-3);
  // Half circumference becomes a straight edge of length π R · (chord polygon).
  const double chord = 2 * 0.05 * std::sin(test::kPi / 32);
  const Vec2 p0 = flat.uv.row(0), p16 = flat.uv.row(16);
  EXPECT_NEAR((p16 - p0).norm(), 16 * chord, 1e-6);
  EXPECT_TRUE(find_overlap(m, boundary_of(m), flat.uv).empty());
}

TEST(Flatten, LscmOnlyIsConformalOnACap) {
  // A spherical cap: LSCM alone keeps angles well, ARAP trades angles for area.
  TriMesh sphere = test::geodesic_sphere(0.1, 6);
  std::vector<int> keep;
  for (int f = 0; f < sphere.num_faces(); ++f) {
    const Vec3 c =
        (sphere.vertices.row(sphere.faces(f, 0)) + sphere.vertices.row(sphere.faces(f, 1)) +
         sphere.vertices.row(sphere.faces(f, 2)))
            .transpose() /
        3.0;
    if (c.y() > 0.05) keep.push_back(f);
  }
  TriMesh cap;
  std::vector<int> id(sphere.num_vertices(), -1);
  std::vector<Vec3> v;
  cap.faces.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      int& x = id[sphere.faces(keep[i], c)];
      if (x < 0) {
        x = static_cast<int>(v.size());
        v.push_back(sphere.vertices.row(sphere.faces(keep[i], c)).transpose());
      }
      cap.faces(static_cast<Eigen::Index>(i), c) = x;
    }
  cap.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i)
    cap.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();

  FlattenOptions lscm_only;
  lscm_only.max_iterations = 0;
  const Flattening conformal = flatten_panel(cap, {boundary_of(cap)}, lscm_only);
  const Flattening arap = flatten_panel(cap, {boundary_of(cap)});
  EXPECT_EQ(conformal.report.flipped, 0);
  EXPECT_EQ(arap.report.flipped, 0);
  EXPECT_LT(conformal.report.mean_angle_error_deg, arap.report.mean_angle_error_deg);
  EXPECT_LT(arap.report.mean_area_distortion, conformal.report.mean_area_distortion);
  EXPECT_GT(arap.iterations, 1);
}

TEST(Flatten, FindsFoldedTriangles) {
  const TriMesh m = half_cylinder(0.05, 0.3, 4, 3);
  Flattening flat = flatten_panel(m, {boundary_of(m)});
  EXPECT_TRUE(find_overlap(m, boundary_of(m), flat.uv).empty());
  flat.uv.row(6) = flat.uv.row(0) - Vec2(1, 1).transpose();  // drag a vertex far outside
  EXPECT_FALSE(find_overlap(m, boundary_of(m), flat.uv).empty());
}

}  // namespace tightfit::flatten_test
