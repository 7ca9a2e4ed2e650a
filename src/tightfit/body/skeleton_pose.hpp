#pragma once
/// Poses of a skeleton (read_skeleton, data/rig/*.joints.json): joint rotations and the
/// rigid motion of every bone they give (forward kinematics).
///
/// Convention (that of BVH files, and of the scene's "rotations"): a pose gives each bone
/// b a rotation L_b about its head, expressed in the BODY frame's axes at rest (x to the
/// body's left, y up, z forward for the MakeHuman bodies). Bone b then moves rigidly by
///   T_b(x) = T_parent(b)(h_b + L_b (x − h_b)),
/// so a rotation turns the bone and everything below it, and the head of a bone follows its
/// parent. Bones the pose does not name keep L = I; all rotations I reproduces the rest
/// skeleton exactly. The root stays where it is (poses carry no translation).
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A rigid motion x ↦ rotation · x + translation (m).
struct RigidMotion {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
};

/// Joint rotations of a pose by bone name (rotation matrices, body frame, see above).
using BoneRotations = std::map<std::string, Mat3>;

/// The rotation of Euler angles `degrees` = (a, b, c) about the axes named by `order`
/// (three letters of X, Y, Z, e.g. "XYZ"): R = R_order[0](a) R_order[1](b) R_order[2](c)
/// (the last-named axis acts on a vector first, as in BVH). Throws std::invalid_argument
/// for an order that is not a permutation of "XYZ".
Mat3 euler_rotation(const Vec3& degrees, std::string_view order);

/// The bones of `skeleton` with every parent before its children. Throws InputError
/// (source `source`) for a parent that is not a bone of the skeleton or a cycle.
std::vector<std::string> bones_parent_first(const std::map<std::string, BoneSegment>& skeleton,
                                            const std::string& source);

/// The rigid motion of every bone of `skeleton` in the pose `rotations` (forward
/// kinematics, see the header comment), by bone name. Throws InputError (source
/// `source`) naming a rotation whose bone the skeleton lacks, or a matrix that is not a
/// rotation (orthonormality or determinant off by more than 1e-6).
std::map<std::string, RigidMotion> pose_skeleton(const std::map<std::string, BoneSegment>& skeleton,
                                                 const BoneRotations& rotations,
                                                 const std::string& source);

}  // namespace tightfit
