#include "tightfit/body/skeleton_pose.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

#include "tightfit/common/error.hpp"

namespace tightfit {

Mat3 euler_rotation(const Vec3& degrees, std::string_view order) {
  if (order.size() != 3 || order.find('X') == std::string_view::npos ||
      order.find('Y') == std::string_view::npos || order.find('Z') == std::string_view::npos)
    throw std::invalid_argument("euler_rotation: order must be a permutation of XYZ");
  Mat3 R = Mat3::Identity();
  for (int k = 0; k < 3; ++k) {
    const Vec3 axis = order[k] == 'X'   ? Vec3::UnitX()
                      : order[k] == 'Y' ? Vec3::UnitY()
                                        : Vec3::UnitZ();
    R = R * Eigen::AngleAxisd(degrees[k] * EIGEN_PI / 180.0, axis).toRotationMatrix();
  }
  return R;
}

std::vector<std::string> bones_parent_first(const std::map<std::string, BoneSegment>& skeleton,
                                            const std::string& source) {
  std::map<std::string, int> state;  // 1: being visited, 2: done
  std::vector<std::string> order;
  order.reserve(skeleton.size());
  for (const auto& [start, bone] : skeleton) {
    std::vector<std::string> chain;
    std::string name = start;
    while (!name.empty() && state[name] == 0) {
      const auto it = skeleton.find(name);
      if (it == skeleton.end())
        throw InputError(source, "bone \"" + chain.back() + "\" has the parent \"" + name +
                                     "\", which is not a bone of the skeleton");
      state[name] = 1;
      chain.push_back(name);
      name = it->second.parent;
    }
    if (!name.empty() && state[name] == 1)
      throw InputError(source, "the parents of bone \"" + name + "\" form a cycle");
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      state[*it] = 2;
      order.push_back(*it);
    }
  }
  return order;
}

std::map<std::string, RigidMotion> pose_skeleton(const std::map<std::string, BoneSegment>& skeleton,
                                                 const BoneRotations& rotations,
                                                 const std::string& source) {
  for (const auto& [name, R] : rotations) {
    if (!skeleton.contains(name))
      throw InputError(source,
                       "the pose rotates \"" + name + "\", which is not a bone of the skeleton");
    if (!R.allFinite() || (R.transpose() * R - Mat3::Identity()).norm() > 1e-6 ||
        std::abs(R.determinant() - 1.0) > 1e-6)
      throw InputError(source, "the rotation of bone \"" + name + "\" is not a rotation matrix");
  }
  std::map<std::string, RigidMotion> motion;
  for (const std::string& name : bones_parent_first(skeleton, source)) {
    const BoneSegment& bone = skeleton.at(name);
    const auto r = rotations.find(name);
    RigidMotion local;  // rotation L about the head: x ↦ h + L (x − h)
    if (r != rotations.end()) {
      local.rotation = r->second;
      local.translation = bone.head - r->second * bone.head;
    }
    if (bone.parent.empty()) {
      motion[name] = local;
    } else {
      const RigidMotion& parent = motion.at(bone.parent);
      motion[name] = {parent.rotation * local.rotation,
                      parent.rotation * local.translation + parent.translation};
    }
  }
  return motion;
}

}  // namespace tightfit
