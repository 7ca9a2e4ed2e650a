#include "tightfit/body/skeleton.hpp"

#include <algorithm>

#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit {

std::map<std::string, BoneSegment> read_skeleton(const std::filesystem::path& path) {
  const nlohmann::json root = read_json_file(path.string());
  const std::string source = path.string();
  if (!root.is_object() || !root.contains("bones") || !root["bones"].is_object())
    throw InputError(source, "/bones: missing (expected an object of bones)");
  std::map<std::string, BoneSegment> bones;
  for (auto it = root["bones"].begin(); it != root["bones"].end(); ++it) {
    JsonFields fields(it.value(), source, "/bones/" + it.key());
    BoneSegment bone;
    bone.name = it.key();
    const nlohmann::json& parent = fields.raw("parent");
    if (parent.is_string())
      bone.parent = parent.get<std::string>();
    else if (!parent.is_null())
      fields.fail("expected a bone name or null", "parent");
    bone.head = fields.vec3("head");
    bone.tail = fields.vec3("tail");
    fields.finish();
    bones.emplace(bone.name, bone);
  }
  if (bones.empty()) throw InputError(source, "/bones: no bones");
  return bones;
}

std::vector<BoneSegment> select_bones(const std::map<std::string, BoneSegment>& skeleton,
                                      const std::vector<std::string>& names,
                                      const std::string& source) {
  std::vector<BoneSegment> out;
  for (const auto& name : names) {
    auto it = skeleton.find(name);
    if (it == skeleton.end())
      throw InputError(source, "no bone named \"" + name + "\" in the skeleton");
    out.push_back(it->second);
  }
  return out;
}

double distance_to_bone(const BoneSegment& bone, const Vec3& p) {
  const Vec3 d = bone.tail - bone.head;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - bone.head).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (bone.head + t * d)).norm();
}

}  // namespace tightfit
