// Skeleton poses, skin-weight transfer and skinning (LBS, DQS) on the MakeHuman rig.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "tightfit/body/body_builder.hpp"
#include "tightfit/body/body_spec.hpp"
#include "tightfit/body/bvh_pose.hpp"
#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skeleton_pose.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/body/skinning.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::skinning_test {

const std::string kRigMesh = TIGHTFIT_DATA_DIR "/bodies/mh_male_regular.obj";
const std::string kRigWeights = TIGHTFIT_DATA_DIR "/rig/default_weights.mhw";
const std::string kRigJoints = TIGHTFIT_DATA_DIR "/rig/mh_male_regular.joints.json";

const SkinWeights& skinning_rig() {
  static const SkinWeights rig = read_skin_weights(kRigMesh, kRigWeights);
  return rig;
}
const std::map<std::string, BoneSegment>& skinning_skeleton() {
  static const auto skeleton = read_skeleton(kRigJoints);
  return skeleton;
}

/// The left knee of the legs body: a band 0.33-0.68 m high, left leg only, tets and
/// weights (surface by closest point from the full body's rig, interior harmonic).
struct KneeBand {
  Body body;
  PointWeights weights;
};
const KneeBand& knee_band() {
  static const KneeBand band = [] {
    const BodySpec spec = parse_body_spec(nlohmann::json::parse(R"({
        "mesh": "data/bodies/mh_legs_male.obj", "edge_length": 0.02,
        "crop": [{"point": [0, 0.33, 0], "normal": [0, 1, 0]}, {"point": [0, 0.68, 0], "normal": [0, -1, 0]},
                 {"point": [0.02, 0, 0], "normal": [1, 0, 0]}]})"),
                                          "/body", TIGHTFIT_SOURCE_DIR, "knee.json");
    KneeBand b;
    b.body = build_body(spec, nullptr);
    b.weights = body_skin_weights(b.body, skinning_rig());
    return b;
  }();
  return band;
}

TEST(SkeletonPose, EulerAnglesComposeInTheOrderNamed) {
  const Vec3 a(30, 45, 60);
  const auto rad = [](double d) { return d * EIGEN_PI / 180.0; };
  const Mat3 expected =
      (Eigen::AngleAxisd(rad(45), Vec3::UnitY()) * Eigen::AngleAxisd(rad(30), Vec3::UnitZ()) *
       Eigen::AngleAxisd(rad(60), Vec3::UnitX()))
          .toRotationMatrix();
  EXPECT_LT((euler_rotation(Vec3(45, 30, 60), "YZX") - expected).norm(), 1e-14);
  EXPECT_LT((euler_rotation(a, "XYZ").determinant() - 1.0), 1e-14);
  EXPECT_THROW(euler_rotation(a, "XXZ"), std::invalid_argument);
}

TEST(SkeletonPose, ChildrenFollowTheirParentAndTheRestPoseIsTheIdentity) {
  const auto& skeleton = skinning_skeleton();
  for (const auto& [name, m] : pose_skeleton(skeleton, {}, "test")) {
    EXPECT_EQ(m.rotation, Mat3::Identity()) << name;
    EXPECT_EQ(m.translation, Vec3::Zero()) << name;
  }
  const Mat3 bend = euler_rotation(Vec3(-40, 0, 0), "XYZ");
  const auto motion = pose_skeleton(skeleton, {{"upperleg02.L", bend}}, "test");
  const BoneSegment& thigh = skeleton.at("upperleg02.L");
  const BoneSegment& shin = skeleton.at("lowerleg01.L");
  // The thigh turns about the hip; the shin's head (the knee) goes with it, unrotated.
  EXPECT_LT((motion.at("upperleg02.L").apply(thigh.head) - thigh.head).norm(), 1e-12);
  const Vec3 knee = thigh.head + bend * (shin.head - thigh.head);
  EXPECT_LT((motion.at("lowerleg01.L").apply(shin.head) - knee).norm(), 1e-12);
  EXPECT_LT((motion.at("lowerleg01.L").rotation - bend).norm(), 1e-14);
  EXPECT_EQ(motion.at("upperleg02.R").rotation, Mat3::Identity());
  EXPECT_THROW(pose_skeleton(skeleton, {{"tail.L", bend}}, "test"), InputError);
  EXPECT_THROW(pose_skeleton(skeleton, {{"upperleg02.L", 2.0 * bend}}, "test"), InputError);
}

TEST(Skinning, TheRestPoseReproducesTheMeshAndWeightsSumToOne) {
  const SkinWeights& rig = skinning_rig();
  const PointWeights w = transfer_skin_weights(rig, rig.vertices);
  ASSERT_EQ(w.num_points(), rig.vertices.rows());
  for (int i = 0; i < w.num_points(); ++i) {
    double total = 0.0;
    for (int k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      EXPECT_GT(w.weight[k], 0.0);
      total += w.weight[k];
    }
    ASSERT_NEAR(total, 1.0, 1e-12) << i;
  }
  const auto rest = pose_skeleton(skinning_skeleton(), {}, "test");
  EXPECT_EQ(apply_motions(blend_motions(w, rest, SkinningMethod::kDualQuaternion), rig.vertices),
            rig.vertices);
  EXPECT_LT((apply_motions(blend_motions(w, rest, SkinningMethod::kLinearBlend), rig.vertices) -
             rig.vertices)
                .cwiseAbs()
                .maxCoeff(),
            1e-14);
}

TEST(Skinning, CroppedBodiesGetWeightsOnTheSurfaceAndHarmonicOnesInside) {
  const KneeBand& band = knee_band();
  ASSERT_EQ(band.weights.num_points(), band.body.num_vertices());
  const VecX leg =
      band.weights.summed({"upperleg01.L", "upperleg02.L", "lowerleg01.L", "lowerleg02.L"});
  for (int v = 0; v < band.body.num_vertices(); ++v) {
    double total = 0.0;
    for (int k = band.weights.offsets[v]; k < band.weights.offsets[v + 1]; ++k)
      total += band.weights.weight[k];
    ASSERT_NEAR(total, 1.0, 1e-12) << v;
    EXPECT_GT(leg[v], 0.9) << "vertex " << v
                           << " of the left knee band is not moved by the left leg";
  }
  // The knee's weights blend thigh and shin across the joint.
  const VecX shin = band.weights.summed({"lowerleg01.L"});
  EXPECT_GT(shin.maxCoeff(), 0.9);
  EXPECT_LT(shin.minCoeff(), 0.1);
}

TEST(Skinning, DualQuaternionsKeepTheKneesVolumeAt90DegreesWhereLinearBlendLosesIt) {
  const KneeBand& band = knee_band();
  const auto knee = pose_skeleton(
      skinning_skeleton(), {{"lowerleg01.L", euler_rotation(Vec3(90, 0, 0), "XYZ")}}, "test");
  const PosedBody dqs = pose_body(band.body, band.body.volume.vertices, band.weights, knee,
                                  SkinningMethod::kDualQuaternion);
  const PosedBody lbs = pose_body(band.body, band.body.volume.vertices, band.weights, knee,
                                  SkinningMethod::kLinearBlend);
  EXPECT_NEAR(dqs.volume_ratio, 1.0, 0.05);
  EXPECT_GT(std::abs(lbs.volume_ratio - 1.0), std::abs(dqs.volume_ratio - 1.0));
  // The ankle end of the band (0.17 m below the knee) swung backwards (−z) by about that.
  double z_before = 1.0, z_after = 1.0;
  for (int v = 0; v < band.body.num_vertices(); ++v)
    if (band.body.volume.vertices(v, 1) < 0.36) {
      z_before = std::min(z_before, band.body.volume.vertices(v, 2));
      z_after = std::min(z_after, dqs.positions(v, 2));
    }
  EXPECT_LT(z_after, z_before - 0.07);
  std::printf("knee band volume ratio: DQS %.4f, LBS %.4f; smallest tet ratio DQS %.3f, LBS %.3f\n",
              dqs.volume_ratio, lbs.volume_ratio, dqs.min_volume_ratio, lbs.min_volume_ratio);
}

TEST(Skinning, AKneeBentBy45DegreesInvertsNoTet) {
  // At 90° the back of the knee folds into itself (a few surface tets there invert: the
  // skinned tissue interpenetrates, as real tissue would be squashed); at 45° it does not.
  const KneeBand& band = knee_band();
  const auto knee = pose_skeleton(
      skinning_skeleton(), {{"lowerleg01.L", euler_rotation(Vec3(45, 0, 0), "XYZ")}}, "test");
  const PosedBody dqs = pose_body(band.body, band.body.volume.vertices, band.weights, knee,
                                  SkinningMethod::kDualQuaternion);
  EXPECT_EQ(dqs.inverted_tets, 0);
  EXPECT_GT(dqs.min_volume_ratio, 0.2);
  EXPECT_NO_THROW(check_posed_body(dqs, band.body, "knee", "test"));
}

TEST(Skinning, LinearBlendCollapsesAHalfTurnTwistAndThePoseCheckSaysSo) {
  const KneeBand& band = knee_band();
  const auto twist = pose_skeleton(
      skinning_skeleton(), {{"lowerleg01.L", euler_rotation(Vec3(0, 180, 0), "XYZ")}}, "test");
  const PosedBody lbs = pose_body(band.body, band.body.volume.vertices, band.weights, twist,
                                  SkinningMethod::kLinearBlend);
  EXPECT_GT(lbs.inverted_tets, 0);
  try {
    check_posed_body(lbs, band.body, "twist", "scene.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pose \"twist\" inverts"), std::string::npos) << e.what();
  }
}

TEST(BvhPose, TheTPoseFileLiftsTheArmsOfTheBodysSkeletonToTheHorizontal) {
  const auto& skeleton = skinning_skeleton();
  const BvhMotion tpose = read_bvh(TIGHTFIT_DATA_DIR "/rig/tpose.bvh");
  const BvhFrameFit fit = fit_bvh_frame(tpose, skeleton);
  EXPECT_NEAR(fit.scale, 0.1, 0.01);  // MakeHuman's decimetres
  EXPECT_LT(fit.rms_residual, 0.03);  // the file's skeleton has MakeHuman's default proportions
  EXPECT_LT(fit.max_residual, 0.05);
  EXPECT_GT(fit.common_joints, 100);
  EXPECT_EQ(fit.unmatched_joints.size(), 10u);  // the file's metatarsals
  // z up in the file, y up in the body: C maps the file's z onto the body's y.
  EXPECT_GT((fit.rotation * Vec3::UnitZ()).dot(Vec3::UnitY()), 0.99);
  const auto motion = pose_skeleton(skeleton, bvh_pose(tpose, 0, fit), tpose.source);
  for (const std::string arm : {"lowerarm01.L", "lowerarm01.R"}) {
    const BoneSegment& bone = skeleton.at(arm);
    const Vec3 rest = (bone.tail - bone.head).normalized();
    const Vec3 posed = motion.at(arm).rotation * rest;
    EXPECT_LT(rest.y(), -0.3) << arm << " hangs down in the A-pose";
    EXPECT_LT(std::abs(posed.y()), 0.1) << arm << " is horizontal in the T-pose";
  }
  EXPECT_THROW(bvh_pose(tpose, 1, fit), InputError);
}

TEST(BvhPose, AFileOfAnotherSkeletonIsRefused) {
  const BvhMotion bench = read_bvh(TIGHTFIT_DATA_DIR "/rig/benchmark.bvh");
  std::map<std::string, BoneSegment> renamed;
  int k = 0;
  for (const auto& [name, bone] : skinning_skeleton())
    renamed[k++ % 3 == 0 ? name : "other." + name] = bone;
  try {
    fit_bvh_frame(bench, renamed);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("are not bones of the skeleton"), std::string::npos)
        << e.what();
  }
  // The same joint names on a skeleton of other proportions: the fit is refused.
  auto stretched = skinning_skeleton();
  for (auto& [name, bone] : stretched)
    if (bone.head.y() < 0.5) bone.head.y() -= 0.5;
  EXPECT_THROW(fit_bvh_frame(bench, stretched), InputError);
}

}  // namespace tightfit::skinning_test
