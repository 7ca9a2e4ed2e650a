#include "tightfit/body/generators.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "support/analytic_shapes.hpp"
#include "tightfit/body/loop_limit.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit::generators_test {

double min_triangle_angle_deg(const TriMesh& m) {
  double min_angle = 180.0;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Vec3 a = m.vertices.row(m.faces(f, i)), b = m.vertices.row(m.faces(f, (i + 1) % 3)),
                 c = m.vertices.row(m.faces(f, (i + 2) % 3));
      min_angle = std::min(
          min_angle, std::acos((b - a).normalized().dot((c - a).normalized())) * 180.0 / M_PI);
    }
  return min_angle;
}

void expect_well_shaped(const TriMesh& m, double h) {
  EXPECT_TRUE(surface_problems(m).empty()) << surface_problems(m).front();  // closed, outward
  EXPECT_GT(min_triangle_angle_deg(m), 25.0);
  const EdgeLengthStats e = edge_length_stats(m);
  EXPECT_GT(e.min, 0.5 * h);
  EXPECT_LT(e.max, 1.7 * h);
  EXPECT_NEAR(e.mean, h, 0.2 * h);
}

TEST(Generators, RoundCappedCylinderIsClosedWellShapedAndOnTheSurface) {
  CylinderParams p;
  p.radius = 0.04;
  p.length = 0.2;
  p.edge_length = 0.008;
  p.fit_limit = false;
  const TriMesh m = cylinder_surface(p);
  expect_well_shaped(m, p.edge_length);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3 x = m.vertices.row(v);
    EXPECT_NEAR((project_to_cylinder(p, x) - x).norm(), 0.0, 1e-12);
  }
  EXPECT_NEAR(signed_volume(m) / test::cylinder_volume(p), 1.0, 0.01);
  EXPECT_NEAR(surface_area(m) / cylinder_area(p), 1.0, 0.01);
}

TEST(Generators, FlatCappedCylinderAlongAnotherAxis) {
  CylinderParams p;
  p.radius = 0.03;
  p.length = 0.1;
  p.caps = CapStyle::kFlat;
  p.axis = Vec3(1, 1, 0);
  p.center = Vec3(0.1, -0.2, 0.3);
  p.fit_limit = false;
  const TriMesh m = cylinder_surface(p);
  expect_well_shaped(m, default_generator_edge_length(p.radius));
  const Vec3 axis = p.axis.normalized();
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3 q = Vec3(m.vertices.row(v)) - p.center;
    EXPECT_LE(std::abs(q.dot(axis)), 0.5 * p.length + 1e-12);
    EXPECT_LE((q - q.dot(axis) * axis).norm(), p.radius + 1e-12);
  }
  EXPECT_NEAR(signed_volume(m) / test::cylinder_volume(p), 1.0, 0.01);
}

TEST(Generators, LimitFitPutsVertexLimitsOnTheAnalyticSurface) {
  CylinderParams c;
  LimitFitResult fit;
  const TriMesh cyl = cylinder_surface(c, &fit);
  EXPECT_LT(fit.max_residual, 1e-9);
  const Points3 limit = loop_limit_positions(cyl);
  for (int v = 0; v < cyl.num_vertices(); ++v) {
    const Vec3 x = limit.row(v);
    EXPECT_NEAR((project_to_cylinder(c, x) - x).norm(), 0.0, 1e-9);
  }
  // Away from the caps the control points sit outside by R α²/8 to leading order
  // (α = 2π/48 the angle between the vertices of a ring).
  const double alpha = 2.0 * std::numbers::pi / 48.0;
  const double h = default_generator_edge_length(c.radius);
  for (int v = 0; v < cyl.num_vertices(); ++v)
    if (std::abs(cyl.vertices(v, 2)) < 0.5 * c.length - 3.0 * h) {
      EXPECT_NEAR(std::hypot(cyl.vertices(v, 0), cyl.vertices(v, 1)) - c.radius,
                  c.radius * alpha * alpha / 8.0, 0.02 * c.radius * alpha * alpha / 8.0);
    }

  SphereParams s;
  s.center = Vec3(1, 2, 3);
  const TriMesh sph = sphere_surface(s, &fit);
  EXPECT_LT(fit.max_residual, 1e-9);
  const Points3 slimit = loop_limit_positions(sph);
  for (int v = 0; v < sph.num_vertices(); ++v)
    EXPECT_NEAR((Vec3(slimit.row(v)) - s.center).norm(), s.radius, 1e-9);
}

TEST(Generators, SphereIsAGeodesicIcosahedron) {
  SphereParams p;
  p.radius = 0.1;
  p.edge_length = 0.02;
  p.fit_limit = false;
  const TriMesh m = sphere_surface(p);
  expect_well_shaped(m, p.edge_length);
  const int k2 = (m.num_vertices() - 2) / 10;  // 10 k² + 2 vertices
  EXPECT_EQ(10 * k2 + 2, m.num_vertices());
  EXPECT_EQ(20 * k2, m.num_faces());
  for (int v = 0; v < m.num_vertices(); ++v) EXPECT_NEAR(m.vertices.row(v).norm(), p.radius, 1e-12);
}

TEST(Generators, DefaultResolutionVolumesWithinOnePercent) {
  for (bool fit : {false, true}) {
    CylinderParams c;
    c.fit_limit = fit;
    EXPECT_NEAR(signed_volume(cylinder_surface(c)) / test::cylinder_volume(c), 1.0, 0.01);
    SphereParams s;
    s.fit_limit = fit;
    EXPECT_NEAR(signed_volume(sphere_surface(s)) / test::sphere_volume(s), 1.0, 0.01);
  }
}

TEST(Generators, RejectsBadParameters) {
  CylinderParams c;
  c.radius = -1.0;
  EXPECT_THROW(cylinder_surface(c), std::invalid_argument);
  c = CylinderParams();
  c.caps = CapStyle::kFlat;
  c.length = 0.0;
  EXPECT_THROW(cylinder_surface(c), std::invalid_argument);
  c = CylinderParams();
  c.axis = Vec3::Zero();
  EXPECT_THROW(cylinder_surface(c), std::invalid_argument);
  SphereParams s;
  s.edge_length = -0.01;
  EXPECT_THROW(sphere_surface(s), std::invalid_argument);
}

TEST(Generators, ZeroLengthRoundCylinderIsASphere) {
  CylinderParams c;
  c.length = 0.0;
  c.fit_limit = false;
  const TriMesh m = cylinder_surface(c);
  EXPECT_TRUE(surface_problems(m).empty());
  SphereParams s;
  s.radius = c.radius;
  EXPECT_NEAR(signed_volume(m) / test::sphere_volume(s), 1.0, 0.01);
}

}  // namespace tightfit::generators_test
