#include "tightfit/body/local_crop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit {
namespace local_crop_test {

/// A torus around the y axis (ring radius R, tube radius r), n × m quads split in two.
TriMesh torus(double R, double r, int n, int m) {
  TriMesh t;
  t.vertices.resize(n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      t.vertices.row(i * m + j) << (R + r * std::cos(v)) * std::cos(u), r * std::sin(v),
          (R + r * std::cos(v)) * std::sin(u);
    }
  t.faces.resize(2 * n * m, 3);
  int f = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m,
                d = i * m + (j + 1) % m;
      t.faces.row(f++) << a, d, c;
      t.faces.row(f++) << a, c, b;
    }
  return t;
}

/// The MakeHuman male regular body and its skeleton.
struct RigBody {
  TriMesh surface = read_tri_mesh(std::string(TIGHTFIT_DATA_DIR) + "/bodies/mh_male_regular.obj");
  std::map<std::string, BoneSegment> skeleton =
      read_skeleton(std::string(TIGHTFIT_DATA_DIR) + "/rig/mh_male_regular.joints.json");

  /// The plane across the left forearm 85 % down it, keeping the elbow's side.
  CropPlane left_wrist(bool local) const {
    const BoneSegment& forearm = skeleton.at("lowerarm02.L");
    return {forearm.head + 0.85 * (forearm.tail - forearm.head),
            -(forearm.tail - forearm.head).normalized(), local};
  }
};

TEST(LocalCrop, TakesOffTheHandAndLeavesTheLegsBehindTheSamePlane) {
  const RigBody body;
  const CropPlane plane = body.left_wrist(true);
  const TriMesh cropped = crop_beyond_nearest_loop(body.surface, plane, "wrist");
  EXPECT_TRUE(
      surface_problems(cropped).empty());  // closed, manifold, outward, no self-intersection

  // In an A-pose the plane across the wrist also passes behind the feet: a plain crop
  // takes them too, the local one only the hand.
  const TriMesh global = crop_and_cap(body.surface, {body.left_wrist(false)});
  auto below_knees = [](const TriMesh& m) {
    int count = 0;
    for (int v = 0; v < m.num_vertices(); ++v) count += m.vertices(v, 1) < 0.3 ? 1 : 0;
    return count;
  };
  EXPECT_EQ(below_knees(cropped), below_knees(body.surface));
  EXPECT_LT(below_knees(global), below_knees(body.surface) - 20);

  // Every vertex removed lies within a hand's length of the wrist, and the cut points
  // (the cap's rim) lie on the plane around the forearm.
  const Vec3 n = plane.normal.normalized();
  int removed = 0;
  for (int v = 0; v < body.surface.num_vertices(); ++v) {
    const Vec3 x = body.surface.vertices.row(v).transpose();
    if (n.dot(x - plane.point) >= 0.0) continue;
    bool kept = false;
    for (int w = 0; w < cropped.num_vertices() && !kept; ++w)
      kept = (cropped.vertices.row(w).transpose() - x).norm() == 0.0;
    if (!kept) {
      ++removed;
      EXPECT_LT((x - plane.point).norm(), 0.25);
    }
  }
  EXPECT_GT(removed, 500);  // the hand with its fingers
  double cap_area = 0.0;
  const VecX areas = face_areas(cropped);
  for (int f = 0; f < cropped.num_faces(); ++f) {
    bool on_plane = true;
    for (int c = 0; c < 3; ++c)
      on_plane = on_plane && std::abs(n.dot(cropped.vertices.row(cropped.faces(f, c)).transpose() -
                                            plane.point)) < 1e-12;
    if (on_plane) cap_area += areas[f];
  }
  EXPECT_GT(cap_area, 5e-4);  // a wrist's cross-section, about 2 cm by 3 cm or more
  EXPECT_LT(cap_area, 5e-3);
  EXPECT_LT(signed_volume(cropped), signed_volume(body.surface));
}

TEST(LocalCrop, TheLoopAroundThePointIsCutEvenWhenAnotherLoopComesNearer) {
  // A hexagonal prism (radius 0.05) and, just outside the middle of one of its sides, a
  // thin octagonal one (radius 0.004): a limb and, beside it, a chin. The point lies
  // inside the hexagon, 8 mm in from that side: the thin prism's cut points are nearer
  // to it than any of the hexagon's, but the loop around the point is the hexagon's.
  const double side = 30.0 * std::numbers::pi / 180.0;
  const Vec3 out_dir(std::cos(side), 0.0, -std::sin(side));  // the side's middle (test mesh frame)
  const TriMesh limb = test::closed_cylinder(0.05, 0.4, 6, 5);
  TriMesh chin = test::closed_cylinder(0.004, 0.4, 8, 5);
  chin.vertices.rowwise() += (0.0493 * out_dir).transpose();
  TriMesh both;
  both.vertices.resize(limb.num_vertices() + chin.num_vertices(), 3);
  both.vertices << limb.vertices, chin.vertices;
  both.faces.resize(limb.num_faces() + chin.num_faces(), 3);
  both.faces << limb.faces, chin.faces.array() + limb.num_vertices();
  ASSERT_TRUE(surface_problems(both).empty());
  const Vec3 point = 0.042 * out_dir + Vec3(0.0, 0.21, 0.0);
  const TriMesh cropped = crop_beyond_nearest_loop(both, {point, -Vec3::UnitY(), true}, "crop");
  EXPECT_TRUE(surface_problems(cropped).empty());
  double limb_top = 0.0, chin_top = 0.0;
  for (int v = 0; v < cropped.num_vertices(); ++v) {
    const Vec3 x = cropped.vertices.row(v).transpose();
    const bool on_chin = (Vec3(x.x(), 0.0, x.z()) - 0.0493 * out_dir).norm() < 0.0041;
    double& top = on_chin ? chin_top : limb_top;
    top = std::max(top, x.y());
  }
  EXPECT_NEAR(limb_top, 0.21, 1e-12);
  EXPECT_NEAR(chin_top, 0.4, 1e-12);
}

TEST(LocalCrop, ALoopAroundAHandleOrAPlaneThatMissesIsAnError) {
  const TriMesh ring = torus(0.2, 0.05, 48, 16);
  ASSERT_TRUE(surface_problems(ring).empty());
  try {
    crop_beyond_nearest_loop(ring, {Vec3(0.2, 0, 0), Vec3::UnitZ(), true}, "crop plane 0");
    FAIL() << "cut through a handle accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "crop plane 0: the cut loop nearest the point does not separate"),
              std::string::npos)
        << e.what();
  }
  try {
    crop_beyond_nearest_loop(ring, {Vec3(0, 1, 0), Vec3::UnitY(), true}, "crop plane 0");
    FAIL() << "plane missing the surface accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("misses the surface"), std::string::npos) << e.what();
  }
}

TEST(LocalCrop, ThePartBeyondTheNearestLoopGoesWholeEvenWhereThePlaneCrossesItAgain) {
  // Half a torus (ring in the xz plane, z > -0.01): a U whose arms end in caps near
  // x = ±0.2. The plane z = 0.1 crosses both arms (x ≈ ±0.17); keeping z < 0.1 with the
  // point on the right arm, the surface beyond the right loop is the arc over the top
  // and the whole left arm, which hangs on it: only the right arm's lower end stays.
  const TriMesh u =
      crop_and_cap(torus(0.2, 0.05, 48, 16), {CropPlane{Vec3(0, 0, -0.01), Vec3::UnitZ(), false}});
  ASSERT_TRUE(surface_problems(u).empty());
  for (const double side : {1.0, -1.0}) {
    SCOPED_TRACE(side);
    const TriMesh one =
        crop_beyond_nearest_loop(u, {Vec3(side * 0.18, 0, 0.1), -Vec3::UnitZ(), true}, "crop");
    EXPECT_TRUE(surface_problems(one).empty());
    EXPECT_NEAR(one.vertices.col(2).maxCoeff(), 0.1, 1e-9);  // cut and capped at z = 0.1
    // Every vertex left is on the point's arm, at least 0.1 m off the ring's axis.
    const double off_axis =
        side > 0 ? one.vertices.col(0).minCoeff() : -one.vertices.col(0).maxCoeff();
    EXPECT_GT(off_axis, 0.1);
  }
}

}  // namespace local_crop_test
}  // namespace tightfit
