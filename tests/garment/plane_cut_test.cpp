#include "tightfit/garment/plane_cut.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit::plane_cut_test {

double area(const TriMesh& m) {
  double a = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 p0 = m.vertices.row(m.faces(f, 0)), p1 = m.vertices.row(m.faces(f, 1)),
               p2 = m.vertices.row(m.faces(f, 2));
    a += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return a;
}

LayoutPlane plane(const Vec3& point, const Vec3& normal) {
  LayoutPlane p;
  p.point = point;
  p.normal = normal.normalized();
  return p;
}

TEST(PlaneCut, InsertsVerticesOnThePlaneAndSplitsCrossedFaces) {
  const TriMesh sphere = test::geodesic_sphere(0.1, 5);
  const std::vector<LayoutPlane> planes{plane(Vec3(0, 0.013, 0), Vec3(0.2, 1, 0.1)),
                                        plane(Vec3(0.004, 0, 0), Vec3(1, 0, 0))};
  const CutMesh cut = cut_by_planes(sphere, planes, 0.0);  // no snapping: the surface is unchanged
  EXPECT_GT(cut.mesh.num_faces(), sphere.num_faces());
  EXPECT_NEAR(area(cut.mesh), area(sphere), 1e-14);
  // Still closed and consistently oriented.
  const SurfaceTopology topo(cut.mesh.faces, cut.mesh.num_vertices());
  EXPECT_TRUE(topo.is_closed());
  EXPECT_TRUE(topo.inconsistently_oriented_edges().empty());
  EXPECT_TRUE(topo.non_manifold_edges().empty());
  for (size_t k = 0; k < planes.size(); ++k) {
    int on = 0;
    for (int v = 0; v < cut.mesh.num_vertices(); ++v)
      if (cut.on_plane[k][v]) {
        ++on;
        EXPECT_NEAR(planes[k].distance(cut.mesh.vertices.row(v).transpose()), 0.0, 1e-15);
      }
    EXPECT_GT(on, 20);
    // No face has corners on both sides of a plane.
    for (int f = 0; f < cut.mesh.num_faces(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int v = cut.mesh.faces(f, c);
        if (!cut.on_plane[k][v]) {
          EXPECT_GT(cut.side[k][f] * planes[k].distance(cut.mesh.vertices.row(v).transpose()), 0.0);
        }
      }
  }
  for (int f = 0; f < cut.mesh.num_faces(); ++f) EXPECT_GE(cut.parent_face[f], 0);
}

TEST(PlaneCut, SnapsNearbyVerticesInsteadOfMakingSlivers) {
  // A plane 1 % of a ring spacing above a ring of the cylinder.
  const TriMesh cylinder = test::open_cylinder(0.05, 0.2, 16, 9);  // rings every 0.025 m
  const std::vector<LayoutPlane> planes{plane(Vec3(0, 0.05025, 0), Vec3(0, 1, 0))};
  const CutMesh snapped = cut_by_planes(cylinder, planes, 0.1);
  EXPECT_EQ(snapped.mesh.num_vertices(), cylinder.num_vertices());  // the ring moved onto the plane
  EXPECT_EQ(snapped.mesh.num_faces(), cylinder.num_faces());
  int on = 0;
  for (int v = 0; v < snapped.mesh.num_vertices(); ++v) on += snapped.on_plane[0][v];
  EXPECT_EQ(on, 16);
  // Snapped along the surface: the vertices stay on the cylinder.
  for (int v = 0; v < snapped.mesh.num_vertices(); ++v) {
    const Vec3 x = snapped.mesh.vertices.row(v);
    EXPECT_NEAR(std::hypot(x.x(), x.z()), 0.05, 1e-15);
  }
  const CutMesh sliver = cut_by_planes(cylinder, planes, 0.0);
  EXPECT_EQ(sliver.mesh.num_vertices(),
            cylinder.num_vertices() + 32);  // a vertical and a diagonal edge per column
}

}  // namespace tightfit::plane_cut_test
