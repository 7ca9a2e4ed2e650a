#pragma once
/// Whether a joints file belongs to a body mesh: a skeleton placed on another body (a
/// child's joints given with a man's mesh, a joints file in another unit or frame) puts
/// joints outside the body, and every layout anchored on it would be cut in the wrong
/// place without a visible error.
#include <filesystem>
#include <map>
#include <string>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// How far (m) a joint may lie outside the body surface: MakeHuman places a few joints
/// (toe tips, the top of the head) on the skin, not under it.
inline constexpr double kJointOutsideTolerance = 0.01;

/// The bone whose subtree check_joints_inside leaves out: MakeHuman's face rig (eyes,
/// lids, tongue, jaw) sits in cavities a closed body surface does not model, up to 31 mm
/// outside it, and the head's tail is the crown, on the skin.
inline constexpr const char* kFaceRigRoot = "head";

/// Checks that the head and tail of every bone (but kFaceRigRoot and the bones under
/// it) lie inside the closed surface `body` (generalized winding number) or within
/// kJointOutsideTolerance of it. Throws InputError (source `joints_file`) naming the
/// joint farthest outside, how far, how many lie outside, and `mesh_file`.
void check_joints_inside(const TriMesh& body, const std::map<std::string, BoneSegment>& skeleton,
                         const std::filesystem::path& joints_file,
                         const std::filesystem::path& mesh_file);

}  // namespace tightfit
