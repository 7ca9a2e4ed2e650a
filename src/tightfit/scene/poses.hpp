#pragma once
/// The rig and the poses of a scene (paper Sec. 5.5; body/posed_body.hpp for what a
/// posed body is):
///
///   "rig": {"mesh": "../data/bodies/mh_male_regular.obj",      // the rigged mesh
///           "weights": "../data/rig/default_weights.mhw",       // its skin weights
///           "joints": "../data/rig/mh_male_regular.joints.json", // its skeleton
///           "skinning": "dual_quaternion" | "linear_blend"},     // default dual_quaternion
///   "poses": [
///     {"name": "stride_1", "bvh": "poses/run.bvh", "frame": 0},  // a BVH frame (0-based)
///     {"name": "knee_90", "rotations": {"lowerleg01.L": [90, 0, 0]}, "order": "XYZ"}
///   ]
///
/// "rotations" gives per bone the Euler angles (degrees) of its rotation about its head,
/// about the BODY frame's axes (x to the body's left, y up, z forward), composed in
/// "order" (default "XYZ": R = R_X(a) R_Y(b) R_Z(c), the last axis acting first, as in
/// BVH); body/skeleton_pose.hpp. A BVH file's own frame and units are fitted onto the
/// skeleton (body/bvh_pose.hpp). Pose names are 1-64 characters of letters, digits,
/// '_', '-' and '.' (they name output files), unique.
///
/// Validation (InputError naming the file and the JSON path): a missing rig file, an
/// unknown bone, a BVH whose joints are not the skeleton's, a frame the file lacks,
/// non-finite angles or angles beyond ±360°, poses without a rig.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tightfit/body/skeleton_pose.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/body/skinning.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit {

/// A rigged mesh: skin weights on its vertices, its skeleton, how to blend.
struct SceneRig {
  SkinWeights weights;
  std::map<std::string, BoneSegment> skeleton;
  SkinningMethod skinning = SkinningMethod::kDualQuaternion;
  std::string source;  ///< "scene.json: /rig", for messages
};

/// One pose of the scene, resolved to bone rotations.
struct ScenePose {
  std::string name;
  BoneRotations rotations;
  std::string origin;  ///< where it came from: "scene.json /poses/1" or "run.bvh frame 3"
  /// BVH joints that rotate but are not bones of the rig (their rotation is not used).
  std::vector<std::string> ignored_joints;
};

/// Parses "rig" (files read and checked). `base_dir` resolves relative paths.
std::shared_ptr<const SceneRig> parse_scene_rig(JsonFields& rig,
                                                const std::filesystem::path& base_dir);

/// Parses the "poses" array `poses` (JSON pointer `path` in `file`) against `rig` (may be
/// null only for an empty array).
std::vector<ScenePose> parse_scene_poses(const nlohmann::json& poses, const std::string& file,
                                         const std::string& path, const SceneRig* rig,
                                         const std::filesystem::path& base_dir);

}  // namespace tightfit
