#include "tightfit/body/skeleton_anchor.hpp"

#include <Eigen/Geometry>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/nearest_word.hpp"

namespace tightfit {
namespace {

/// The body frame's axes by name (x to the body's left, y up, z forward).
const std::map<std::string, Vec3>& body_axes() {
  static const std::map<std::string, Vec3> axes = {
      {"left", Vec3::UnitX()},  {"right", -Vec3::UnitX()}, {"up", Vec3::UnitY()},
      {"down", -Vec3::UnitY()}, {"front", Vec3::UnitZ()},  {"back", -Vec3::UnitZ()}};
  return axes;
}

}  // namespace

void parse_anchored_point(JsonFields& f, const std::string& key, Vec3& point,
                          std::optional<BoneAnchor>& anchor) {
  const nlohmann::json& value = f.raw(key);
  if (value.is_object()) {
    JsonFields af(value, f.source(), f.child_path(key));
    BoneAnchor a;
    a.bone = af.string("bone");
    if (a.bone.empty()) af.fail("expected a bone name", "bone");
    a.at = af.number("at");
    if (!(a.at >= 0.0 && a.at <= 1.0))
      af.fail("must lie in [0, 1] (a fraction of the bone from its head to its tail)", "at");
    af.finish();
    anchor = a;
  } else if (value.is_array() || value.is_null()) {
    point = f.vec3(key);
  } else {
    f.fail("expected [x, y, z] (m) or a bone anchor {\"bone\": NAME, \"at\": fraction}", key);
  }
}

void parse_anchored_direction(JsonFields& f, const std::string& key,
                              const std::optional<BoneAnchor>& point_anchor, Vec3& direction,
                              std::optional<BoneDirection>& along_bone) {
  const nlohmann::json& value = f.raw(key);
  if (value.is_string()) {
    const std::string word = value.get<std::string>();
    if (word == "along_bone" || word == "-along_bone") {
      if (!point_anchor)
        f.fail("\"" + word +
                   "\" needs a bone anchor as \"point\" (or name the bone: "
                   "{\"along_bone\": NAME})",
               key);
      along_bone = BoneDirection{point_anchor->bone, word[0] == '-' ? -1.0 : 1.0, ""};
    } else if (const auto it = body_axes().find(word); it != body_axes().end()) {
      direction = it->second;
    } else {
      f.fail(
          "expected [x, y, z], a body axis (left, right, up, down, front, back), "
          "\"along_bone\" or \"-along_bone\", got \"" +
              word + "\"",
          key);
    }
  } else if (value.is_object()) {
    JsonFields nf(value, f.source(), f.child_path(key));
    BoneDirection d;
    if (nf.has("across_bones")) {
      const nlohmann::json& bones = nf.raw("across_bones");
      if (!bones.is_array() || bones.size() != 2 || !bones[0].is_string() ||
          !bones[1].is_string() || bones[0].get<std::string>().empty() ||
          bones[1].get<std::string>().empty())
        nf.fail("expected two bone names", "across_bones");
      if (nf.has("along_bone"))
        nf.fail("give either \"along_bone\" or \"across_bones\"", "along_bone");
      d.bone = bones[0].get<std::string>();
      d.across = bones[1].get<std::string>();
      if (d.bone == d.across) nf.fail("expected two different bones", "across_bones");
    } else {
      d.bone = nf.string("along_bone");
      if (d.bone.empty()) nf.fail("expected a bone name", "along_bone");
    }
    d.sign = nf.boolean("reversed", false) ? -1.0 : 1.0;
    nf.finish();
    along_bone = d;
  } else if (value.is_array() || value.is_null()) {
    const Vec3 n = f.vec3(key);
    if (n.norm() < 1e-12) f.fail("the normal must not be zero", key);
    direction = n.normalized();
  } else {
    f.fail(
        "expected [x, y, z], a body axis, \"along_bone\", {\"along_bone\": NAME} or "
        "{\"across_bones\": [A, B]}",
        key);
  }
}

const BoneSegment& find_anchor_bone(const std::map<std::string, BoneSegment>& skeleton,
                                    const std::string& name, const std::string& source,
                                    const std::string& path, const std::string& skeleton_source) {
  const auto it = skeleton.find(name);
  if (it != skeleton.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& entry : skeleton) names.push_back(entry.first);
  const std::string near = nearest_word(name, names);
  throw InputError(source, path + ": unknown bone \"" + name + "\" (not in the skeleton of " +
                               skeleton_source + ")" +
                               (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
}

Vec3 anchor_point(const BoneSegment& bone, double at) {
  return bone.head + at * (bone.tail - bone.head);
}

Vec3 resolve_bone_direction(const BoneDirection& direction,
                            const std::map<std::string, BoneSegment>& skeleton,
                            const std::string& source, const std::string& path,
                            const std::string& skeleton_source) {
  auto unit_along = [&](const std::string& name) -> Vec3 {
    const BoneSegment& bone = find_anchor_bone(skeleton, name, source, path, skeleton_source);
    const Vec3 d = bone.tail - bone.head;
    if (!(d.norm() > 1e-9))
      throw InputError(source,
                       path + ": bone \"" + name + "\" has zero length: it gives no direction");
    return d.normalized();
  };
  const Vec3 along = unit_along(direction.bone);
  if (direction.across.empty()) return direction.sign * along;
  const Vec3 normal = along.cross(unit_along(direction.across));
  if (!(normal.norm() > 1e-3))  // bones within 0.06 degrees of parallel
    throw InputError(source, path + ": bones \"" + direction.bone + "\" and \"" + direction.across +
                                 "\" are parallel: they span no plane");
  return direction.sign * normal.normalized();
}

}  // namespace tightfit
