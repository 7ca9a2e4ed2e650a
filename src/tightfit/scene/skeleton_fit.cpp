#include "tightfit/scene/skeleton_fit.hpp"

#include <cstdio>

#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {

void check_joints_inside(const TriMesh& body, const std::map<std::string, BoneSegment>& skeleton,
                         const std::filesystem::path& joints_file,
                         const std::filesystem::path& mesh_file) {
  // Whether `name` is the face rig's root or under it (parents followed up to the root).
  auto in_face_rig = [&](std::string name) {
    for (size_t depth = 0; !name.empty() && depth <= skeleton.size(); ++depth) {
      if (name == kFaceRigRoot) return true;
      const auto it = skeleton.find(name);
      if (it == skeleton.end()) return false;
      name = it->second.parent;
    }
    return false;
  };
  const SurfaceDistance surface(body);
  int outside = 0;
  double farthest = 0.0;
  std::string where;
  for (const auto& [name, bone] : skeleton) {
    if (in_face_rig(name)) continue;
    for (const auto& [end, p] : {std::pair{"head", bone.head}, std::pair{"tail", bone.tail}}) {
      if (surface.contains(p)) continue;
      const double distance = surface.distance(p);
      if (distance <= kJointOutsideTolerance) continue;
      ++outside;
      if (distance <= farthest) continue;
      farthest = distance;
      char text[200];
      std::snprintf(text, sizeof text,
                    "the %s of bone \"%s\" (%.3f, %.3f, %.3f) m lies %.0f mm outside", end,
                    name.c_str(), p.x(), p.y(), p.z(), distance * 1000.0);
      where = text;
    }
  }
  if (outside > 0)
    throw InputError(joints_file.string(),
                     where + " the body " + mesh_file.string() + " (" + std::to_string(outside) +
                         " joints lie more than " +
                         std::to_string(static_cast<int>(kJointOutsideTolerance * 1000.0)) +
                         " mm outside it): this skeleton was not placed on "
                         "this body (another body's joints file, or another unit or frame)");
}

}  // namespace tightfit
