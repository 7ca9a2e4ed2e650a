#include "tightfit/body/pinned_core.hpp"

#include <gtest/gtest.h>

#include "tightfit/body/generators.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/tetrahedralize.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::pinned_core_test {

struct Cylinder {
  CylinderParams params;
  TriMesh surface;
  TetMesh volume;
};

Cylinder make_cylinder(const Points3& interior = Points3(0, 3)) {
  Cylinder c;
  c.params.radius = 0.05;
  c.params.length = 0.2;
  c.params.edge_length = 0.012;
  c.surface = cylinder_surface(c.params);
  TetQuality q;
  q.max_volume = regular_tet_volume(0.02);
  c.volume = tetrahedralize_surface(c.surface, q, interior);
  return c;
}

/// Distance from the axis segment of the capsule.
double axis_distance(const CylinderParams& p, const Vec3& x) {
  const double z = std::clamp(x.z(), -0.5 * p.length, 0.5 * p.length);
  return (x - Vec3(0, 0, z)).norm();
}

TEST(PinnedCore, SoftTissueDepthPinsExactlyTheDeepVertices) {
  const Cylinder c = make_cylinder();
  const SurfaceDistance distance(c.surface);
  CoreOptions o;
  o.soft_tissue = 0.015;
  const std::vector<int> pinned = pinned_core(c.volume, c.surface.num_vertices(), distance, o);
  ASSERT_FALSE(pinned.empty());
  EXPECT_TRUE(std::is_sorted(pinned.begin(), pinned.end()));
  std::vector<char> is_pinned(c.volume.num_vertices(), 0);
  for (int v : pinned) is_pinned[v] = 1;
  for (int v = 0; v < c.volume.num_vertices(); ++v) {
    const Vec3 x = c.volume.vertices.row(v);
    const bool deep = v >= c.surface.num_vertices() && distance.distance(x) >= 0.015;
    EXPECT_EQ(is_pinned[v] != 0, deep) << v;
    // The control mesh is within a fraction of a millimetre of the capsule.
    if (is_pinned[v]) {
      EXPECT_LE(axis_distance(c.params, x), c.params.radius - 0.015 + 5e-4);
    }
  }
}

TEST(PinnedCore, NothingDeepEnoughIsAnInputErrorNamingTheSource) {
  const Cylinder c = make_cylinder();
  const SurfaceDistance distance(c.surface);
  CoreOptions o;
  o.soft_tissue = 0.06;
  o.source = "spec.json: /core";
  try {
    pinned_core(c.volume, c.surface.num_vertices(), distance, o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "spec.json: /core");
    EXPECT_NE(std::string(e.what()).find("no vertex is pinned"), std::string::npos);
  }
}

TEST(PinnedCore, BoneSamplesBecomePinnedVertices) {
  CoreOptions o;
  o.bones = {BoneSegment{"axis", "", Vec3(0, 0, -0.2), Vec3(0, 0, 0.2)}};
  o.bone_radius = 0.0;
  o.bone_sample_spacing = 0.02;
  o.bone_sample_clearance = 0.005;
  Cylinder probe = make_cylinder();
  const SurfaceDistance probe_distance(probe.surface);
  const Points3 samples = bone_sample_points(o, probe_distance);
  // The bone reaches 0.2 m, the capsule 0.15 m: samples up to |z| ≤ 0.145 m are kept.
  ASSERT_EQ(samples.rows(), 15);
  EXPECT_LE(samples.col(2).cwiseAbs().maxCoeff(), 0.14 + 1e-12);
  const Cylinder c = make_cylinder(samples);
  const SurfaceDistance distance(c.surface);
  const std::vector<int> pinned = pinned_core(c.volume, c.surface.num_vertices(), distance, o,
                                              static_cast<int>(samples.rows()));
  std::vector<int> expected;
  for (int i = 0; i < samples.rows(); ++i) expected.push_back(c.surface.num_vertices() + i);
  EXPECT_EQ(pinned, expected);
}

TEST(PinnedCore, SoftTissueDepthAddsToTheAlwaysPinnedVertices) {
  // Bone samples (always pinned) stay pinned when a soft-tissue depth is given too, even
  // where they are shallower than that depth; deep vertices are pinned in addition.
  CoreOptions o;
  o.bones = {BoneSegment{"axis", "", Vec3(0, 0, -0.2), Vec3(0, 0, 0.2)}};
  o.bone_radius = 0.0;
  o.bone_sample_spacing = 0.02;
  o.bone_sample_clearance = 0.005;
  o.soft_tissue = 0.045;
  Cylinder probe = make_cylinder();
  const Points3 samples = bone_sample_points(o, SurfaceDistance(probe.surface));
  const Cylinder c = make_cylinder(samples);
  const SurfaceDistance distance(c.surface);
  const int n = c.surface.num_vertices(), k = static_cast<int>(samples.rows());
  const std::vector<int> pinned = pinned_core(c.volume, n, distance, o, k);
  std::vector<int> expected;
  int shallow_samples = 0;
  for (int v = n; v < c.volume.num_vertices(); ++v) {
    const bool deep = distance.distance(c.volume.vertices.row(v)) >= 0.045;
    if (v < n + k && !deep) ++shallow_samples;
    if (v < n + k || deep) expected.push_back(v);
  }
  EXPECT_GT(shallow_samples, 0);  // the samples near the caps are shallower than 45 mm
  EXPECT_EQ(pinned, expected);
}

TEST(Skeleton, ReadsTheMakeHumanJointsFile) {
  const auto bones = read_skeleton(TIGHTFIT_DATA_DIR "/rig/mh_male_regular.joints.json");
  EXPECT_EQ(bones.size(), 163u);
  const BoneSegment& thigh = bones.at("upperleg02.L");
  EXPECT_EQ(thigh.parent, "upperleg01.L");
  EXPECT_NEAR(thigh.head.y(), 0.838812, 1e-9);
  EXPECT_NEAR(thigh.tail.y(), 0.505075, 1e-9);
  EXPECT_TRUE(bones.at("root").parent.empty());
  EXPECT_NEAR(distance_to_bone(thigh, thigh.head), 0.0, 1e-15);
  EXPECT_THROW(select_bones(bones, {"tail.L"}, "core"), InputError);
  EXPECT_THROW(read_skeleton(TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj"), InputError);
}

TEST(Skeleton, DistanceToBoneSegment) {
  const BoneSegment b{"b", "", Vec3(0, 0, 0), Vec3(0, 1, 0)};
  EXPECT_NEAR(distance_to_bone(b, Vec3(0.3, 0.5, 0)), 0.3, 1e-15);
  EXPECT_NEAR(distance_to_bone(b, Vec3(0, 2, 0)), 1.0, 1e-15);
  EXPECT_NEAR(distance_to_bone(b, Vec3(0, -0.5, 0.5)), std::sqrt(0.5), 1e-15);
}

}  // namespace tightfit::pinned_core_test
