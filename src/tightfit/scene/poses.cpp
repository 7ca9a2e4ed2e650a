#include "tightfit/scene/poses.hpp"

#include <cctype>
#include <cmath>
#include <set>

#include "tightfit/body/bvh.hpp"
#include "tightfit/body/bvh_pose.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

std::filesystem::path resolve(const std::filesystem::path& base_dir, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_relative() ? base_dir / p : p;
}

bool valid_pose_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return name != "." && name != "..";
}

BoneRotations parse_rotations(JsonFields& pose, const SceneRig& rig) {
  const std::string order = pose.choice("order", {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"}, "XYZ");
  const nlohmann::json& rotations = pose.raw("rotations");
  if (!rotations.is_object() || rotations.empty())
    pose.fail("expected an object of bones, each [a, b, c] in degrees", "rotations");
  BoneRotations out;
  for (auto it = rotations.begin(); it != rotations.end(); ++it) {
    const std::string key = "rotations/" + it.key();
    if (!rig.skeleton.contains(it.key()))
      pose.fail("the rig's skeleton has no bone \"" + it.key() + "\"", key);
    const nlohmann::json& a = it.value();
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() ||
        !a[2].is_number())
      pose.fail("expected [a, b, c] in degrees", key);
    const Vec3 degrees(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
    if (!degrees.allFinite() || degrees.cwiseAbs().maxCoeff() > 360.0)
      pose.fail("angles must be finite and within ±360 degrees", key);
    out[it.key()] = euler_rotation(degrees, order);
  }
  return out;
}

}  // namespace

std::shared_ptr<const SceneRig> parse_scene_rig(JsonFields& f,
                                                const std::filesystem::path& base_dir) {
  auto file = [&](const std::string& key) {
    const std::string name = f.string(key);
    if (name.empty()) f.fail("must name a file", key);
    return resolve(base_dir, name);
  };
  const auto mesh = file("mesh"), weights = file("weights"), joints = file("joints");
  auto rig = std::make_shared<SceneRig>();
  rig->skinning =
      f.choice("skinning", {"dual_quaternion", "linear_blend"}, "dual_quaternion") == "linear_blend"
          ? SkinningMethod::kLinearBlend
          : SkinningMethod::kDualQuaternion;
  rig->source = f.source() + ": " + f.path();
  f.finish();
  rig->weights = read_skin_weights(mesh, weights);
  rig->skeleton = read_skeleton(joints);
  bones_parent_first(rig->skeleton, joints.string());  // parents exist, no cycles
  for (const auto& [bone, entries] : rig->weights.bones)
    if (!entries.empty() && !rig->skeleton.contains(bone))
      throw InputError(weights.string(), "weights for bone \"" + bone + "\", which the skeleton " +
                                             joints.string() + " does not have");
  return rig;
}

std::vector<ScenePose> parse_scene_poses(const nlohmann::json& poses, const std::string& file,
                                         const std::string& path, const SceneRig* rig,
                                         const std::filesystem::path& base_dir) {
  if (!poses.is_array()) throw InputError(file, path + ": expected an array of poses");
  if (!poses.empty() && rig == nullptr)
    throw InputError(file,
                     path + ": poses need a rig (\"rig\": {\"mesh\", \"weights\", \"joints\"})");
  std::vector<ScenePose> out;
  std::set<std::string> names;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    JsonFields pose(poses[k], file, path + "/" + std::to_string(k));
    ScenePose p;
    p.name = pose.string("name");
    if (!valid_pose_name(p.name))
      pose.fail("must be 1-64 letters, digits, '_', '-' or '.' (it names output files)", "name");
    if (!names.insert(p.name).second) pose.fail("another pose has this name", "name");
    const bool has_bvh = pose.has("bvh"), has_rotations = pose.has("rotations");
    if (has_bvh == has_rotations)
      pose.fail("give either \"bvh\" (with \"frame\") or \"rotations\"");
    if (has_bvh) {
      const std::filesystem::path bvh_file = resolve(base_dir, pose.string("bvh"));
      const int frame = pose.integer("frame", 0);
      if (frame < 0) pose.fail("must be >= 0", "frame");
      const BvhMotion motion = read_bvh(bvh_file);
      p.rotations =
          bvh_pose(motion, frame, fit_bvh_frame(motion, rig->skeleton), &p.ignored_joints);
      p.origin = bvh_file.string() + " frame " + std::to_string(frame);
    } else {
      p.rotations = parse_rotations(pose, *rig);
      p.origin = file + " " + pose.path();
    }
    pose.finish();
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace tightfit
