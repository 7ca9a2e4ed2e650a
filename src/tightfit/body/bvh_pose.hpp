#pragma once
/// Poses from BVH motion files (bvh.hpp) for a body's skeleton (skeleton.hpp).
///
/// A BVH file has its own frame and units (MakeHuman's: z up, decimetres). Its rest
/// skeleton — the joint positions its OFFSETs give — is fitted onto the body's skeleton
/// by the similarity (scale s, rotation C, translation) that best maps the BVH joints onto
/// the heads of the bones of the same name (least squares, Umeyama 1991). A BVH joint's
/// rotation R (its Euler channels, in the BVH frame's axes at rest) becomes the bone
/// rotation L = C R Cᵀ in the body frame (skeleton_pose.hpp's convention, which is
/// BVH's). Translations (the root's and any joint's position channels) are not used: the
/// skeleton's bone lengths are the body's, and the body stays where it stands.
#include <map>
#include <string>
#include <vector>

#include "tightfit/body/bvh.hpp"
#include "tightfit/body/skeleton_pose.hpp"

namespace tightfit {

/// The fitted map from the BVH frame to the body frame, x_body ≈ s C x_bvh + t.
struct BvhFrameFit {
  double scale = 1.0;                ///< s (body metres per BVH unit)
  Mat3 rotation = Mat3::Identity();  ///< C
  Vec3 translation = Vec3::Zero();   ///< t (m)
  double max_residual = 0.0;         ///< largest joint distance after the fit (m)
  double rms_residual = 0.0;         ///< root mean square of those distances (m)
  int common_joints = 0;             ///< joints fitted
  /// BVH joints that are not bones of the skeleton (their rotations are not used; the
  /// joints below them still are).
  std::vector<std::string> unmatched_joints;
};

/// Fits the BVH's rest skeleton onto `skeleton` (on the joints both have; MakeHuman's
/// BVH files have a few joints its joints files lack, e.g. metatarsals). Throws
/// InputError (source `motion.source`) when fewer than half of the BVH's joints (or
/// fewer than 3) are bones of the skeleton (a few are named), or when the fitted joints
/// miss the bones' heads by more than 5 % of the skeleton's size (a BVH of another
/// skeleton).
BvhFrameFit fit_bvh_frame(const BvhMotion& motion,
                          const std::map<std::string, BoneSegment>& skeleton);

/// The bone rotations of frame `frame` (0-based) in the body frame. Rotations of
/// unmatched joints are left out; the names of those that rotate by more than 1° are
/// added to `*ignored` when given. Throws InputError naming the file for a frame beyond
/// the file's frames.
BoneRotations bvh_pose(const BvhMotion& motion, int frame, const BvhFrameFit& fit,
                       std::vector<std::string>* ignored = nullptr);

}  // namespace tightfit
