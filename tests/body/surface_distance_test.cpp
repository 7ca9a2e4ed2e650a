#include "tightfit/body/surface_distance.hpp"

#include <gtest/gtest.h>

#include "tightfit/body/generators.hpp"

namespace tightfit::surface_distance_test {

TEST(SurfaceDistance, SphereDistancesAndInside) {
  SphereParams p;
  p.radius = 0.1;
  p.fit_limit = false;
  const TriMesh m = sphere_surface(p);
  const SurfaceDistance d(m);
  // Inscribed polyhedron: distances from the centre lie between the inradius and R.
  EXPECT_LT(d.distance(Vec3::Zero()), p.radius);
  EXPECT_GT(d.distance(Vec3::Zero()), 0.98 * p.radius);
  EXPECT_NEAR(d.distance(Vec3(0.3, 0, 0)), 0.2, 0.002);
  const Vec3 v = m.vertices.row(7);
  EXPECT_NEAR(d.distance(1.5 * v), 0.5 * p.radius, 1e-12);
  EXPECT_NEAR((d.closest_point(1.5 * v) - v).norm(), 0.0, 1e-12);
  EXPECT_NEAR(d.winding_number(Vec3(0.01, 0.02, -0.03)), 1.0, 1e-9);
  EXPECT_NEAR(d.winding_number(Vec3(0.2, 0, 0)), 0.0, 1e-9);
  EXPECT_TRUE(d.contains(Vec3(0.09, 0, 0)));
  EXPECT_FALSE(d.contains(Vec3(0.11, 0, 0)));
}

}  // namespace tightfit::surface_distance_test
