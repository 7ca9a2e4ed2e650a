#pragma once
/// Bone segments of a skeleton placed on a body, read from a joints file
/// (data/rig/*.joints.json): {"bones": {NAME: {"parent": NAME or null,
/// "head": [x, y, z], "tail": [x, y, z]}, ...}} in metres, in the body's frame.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// One bone: the segment from `head` to `tail` (m).
struct BoneSegment {
  std::string name;
  std::string parent;  ///< empty for the root
  Vec3 head = Vec3::Zero();
  Vec3 tail = Vec3::Zero();
};

/// All bones of a joints file by name. Throws InputError naming the file and the JSON
/// path of a malformed entry. Other top-level keys (description, shape) are ignored.
std::map<std::string, BoneSegment> read_skeleton(const std::filesystem::path& path);

/// The named bones of `skeleton`, in the order of `names`. Throws InputError
/// (source `source`) naming a bone that does not exist.
std::vector<BoneSegment> select_bones(const std::map<std::string, BoneSegment>& skeleton,
                                      const std::vector<std::string>& names,
                                      const std::string& source);

/// Distance (m) from `p` to the segment head–tail of `bone`.
double distance_to_bone(const BoneSegment& bone, const Vec3& p);

}  // namespace tightfit
