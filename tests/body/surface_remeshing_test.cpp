#include "tightfit/body/surface_remeshing.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tightfit/body/generators.hpp"
#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit::surface_remeshing_test {

TriMesh sphere(double radius, double edge) {
  SphereParams p;
  p.radius = radius;
  p.edge_length = edge;
  p.fit_limit = false;
  return sphere_surface(p);
}

/// Area of the faces with all corners on the plane y = 0.
double cap_area(const TriMesh& m) {
  double area = 0.0;
  const VecX areas = face_areas(m);
  for (int f = 0; f < m.num_faces(); ++f) {
    bool on = true;
    for (int c = 0; c < 3; ++c) on = on && std::abs(m.vertices(m.faces(f, c), 1)) < 1e-12;
    if (on) area += areas[f];
  }
  return area;
}

TEST(CropAndCap, HalfSphereKeepsTheSideTheNormalPointsTo) {
  const TriMesh s = sphere(0.1, 0.02);
  const TriMesh half = crop_and_cap(s, {CropPlane{Vec3::Zero(), Vec3(0, 2, 0)}});
  EXPECT_TRUE(surface_problems(half).empty());  // closed, manifold, outward, no self-intersection
  EXPECT_GE(half.vertices.col(1).minCoeff(), -1e-15);
  // The geodesic sphere is symmetric under y → −y: half of its volume, up to the
  // 1e-7·diagonal push of the vertices on the plane.
  EXPECT_NEAR(signed_volume(half), 0.5 * signed_volume(s), 1e-6 * signed_volume(s));
  EXPECT_GT(cap_area(half), 0.95 * M_PI * 0.01);
}

TEST(CropAndCap, PlanesThatMissKeepOrRemoveEverything) {
  const TriMesh s = sphere(0.1, 0.03);
  const TriMesh same = crop_and_cap(s, {CropPlane{Vec3(0, -1, 0), Vec3(0, 1, 0)}});
  EXPECT_NEAR(signed_volume(same), signed_volume(s), 1e-15);
  EXPECT_THROW(crop_and_cap(s, {CropPlane{Vec3(0, 1, 0), Vec3(0, 1, 0)}}), InputError);
  EXPECT_THROW(crop_and_cap(s, {CropPlane{Vec3::Zero(), Vec3::Zero()}}), InputError);
}

TEST(RemeshIsotropic, ReachesTheTargetEdgeLengthOnTheInputSurface) {
  const TriMesh coarse = sphere(0.1, 0.04);
  RemeshOptions o;
  o.edge_length = 0.01;
  const RemeshResult r = remesh_isotropic(coarse, o);
  EXPECT_TRUE(surface_problems(r.mesh).empty());
  const EdgeLengthStats e = edge_length_stats(r.mesh);
  EXPECT_NEAR(e.mean, o.edge_length, 0.2 * o.edge_length);
  EXPECT_GT(e.min, 0.3 * o.edge_length);
  EXPECT_LT(e.max, 1.5 * o.edge_length);
  const SurfaceDistance input(coarse);
  for (int v = 0; v < r.mesh.num_vertices(); ++v)
    EXPECT_LT(input.distance(r.mesh.vertices.row(v)), 1e-9);
  EXPECT_NEAR(signed_volume(r.mesh) / signed_volume(coarse), 1.0, 0.02);
}

TEST(RemeshIsotropic, CapBorderAndCapStayInTheirPlane) {
  const TriMesh half = crop_and_cap(sphere(0.1, 0.02), {CropPlane{Vec3::Zero(), Vec3::UnitY()}});
  RemeshOptions o;
  o.edge_length = 0.01;
  o.cap_planes = {CropPlane{Vec3::Zero(), Vec3::UnitY()}};
  const RemeshResult r = remesh_isotropic(half, o);
  EXPECT_TRUE(surface_problems(r.mesh).empty());
  EXPECT_GT(r.feature_edges, 0);
  // Nothing bulges through the cap, the cap stays flat and keeps its area.
  EXPECT_GE(r.mesh.vertices.col(1).minCoeff(), -1e-12);
  EXPECT_NEAR(cap_area(r.mesh) / cap_area(half), 1.0, 0.02);
  EXPECT_NEAR(signed_volume(r.mesh) / signed_volume(half), 1.0, 0.02);
}

TEST(RemeshIsotropic, ClosedCreaseLoopsAreKept) {
  CylinderParams p;
  p.caps = CapStyle::kFlat;
  p.radius = 0.05;
  p.length = 0.2;
  p.edge_length = 0.02;
  p.fit_limit = false;
  const TriMesh cyl = cylinder_surface(p);
  RemeshOptions o;
  o.edge_length = 0.01;
  const RemeshResult r = remesh_isotropic(cyl, o);
  EXPECT_EQ(r.feature_edges,
            2 * static_cast<int>(std::lround(2 * M_PI * p.radius / p.edge_length)));
  // The rims stay sharp: every vertex is on the cylinder or on a cap disc, and the caps
  // stay at z = ±L/2.
  int on_rim = 0;
  for (int v = 0; v < r.mesh.num_vertices(); ++v) {
    const Vec3 x = r.mesh.vertices.row(v);
    const double rho = std::hypot(x.x(), x.y());
    EXPECT_LE(std::abs(x.z()), 0.5 * p.length + 1e-12);
    EXPECT_LE(rho, p.radius + 1e-12);
    if (std::abs(std::abs(x.z()) - 0.5 * p.length) < 1e-12 &&
        rho > p.radius * std::cos(M_PI / 16) - 1e-12)
      ++on_rim;
  }
  EXPECT_GT(on_rim, 2 * 16);
  EXPECT_NEAR(signed_volume(r.mesh) / signed_volume(cyl), 1.0, 0.01);
}

TEST(RemeshIsotropic, RefinesWhereTheUniformResultIntersectsItself) {
  // At 5 mm the closed lips of the head come out intersecting; local refinement fixes it.
  const TriMesh head = read_tri_mesh(TIGHTFIT_DATA_DIR "/bodies/mh_head_neutral.obj");
  RemeshOptions o;
  o.edge_length = 0.005;
  o.max_refinements = 0;
  EXPECT_THROW(remesh_isotropic(head, o), InputError);
  o.max_refinements = 3;
  const RemeshResult r = remesh_isotropic(head, o);
  EXPECT_GE(r.refinements, 1);
  EXPECT_TRUE(surface_problems(r.mesh).empty());  // includes the self-intersection test
  EXPECT_NEAR(signed_volume(r.mesh) / signed_volume(head), 1.0, 0.01);
}

TEST(RemeshIsotropic, RejectsBadOptions) {
  RemeshOptions o;
  o.edge_length = 0.0;
  EXPECT_THROW(remesh_isotropic(sphere(0.1, 0.03), o), InputError);
}

}  // namespace tightfit::surface_remeshing_test
