#pragma once
/// Skinning: how a pose of the skeleton (skeleton_pose.hpp) moves the points of a body.
/// Every point p carries skin weights w_b(p) ≥ 0 over a few bones, summing to 1, and
/// moves by a blend of its bones' rigid motions T_b:
///  * linear blend skinning (LBS): p ↦ Σ_b w_b T_b(p), an affine map per point that is
///    not rigid where bones disagree: volume collapses at strongly bent joints (the
///    "candy wrapper" and knee/elbow collapse);
///  * dual-quaternion skinning (DQS, Kavan et al. 2008, the default): the normalized
///    weighted sum of the bones' unit dual quaternions, a RIGID motion per point, which
///    keeps volume at bent joints (tests: a 90° knee).
#include <map>
#include <string>
#include <vector>

#include "tightfit/body/skeleton_pose.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// Skin weights of n points in compressed rows: the entries of point i are
/// [offsets[i], offsets[i+1]), each a bone index into `bones` and a weight > 0; the
/// weights of each point sum to 1.
struct PointWeights {
  std::vector<std::string> bones;
  std::vector<int> offsets{0};  ///< n + 1
  std::vector<int> bone;        ///< per entry
  std::vector<double> weight;   ///< per entry

  int num_points() const { return static_cast<int>(offsets.size()) - 1; }
  /// Appends a point with the given (bone index, weight) entries (weights > 0, any sum:
  /// they are normalized here). Throws std::invalid_argument for no positive weight.
  void add_point(const std::vector<std::pair<int, double>>& entries);
  /// Σ_b w_b(p) over the named bones for every point (n, in [0, 1]); unknown names add 0.
  VecX summed(const std::vector<std::string>& names) const;
};

enum class SkinningMethod { kLinearBlend, kDualQuaternion };

/// "linear_blend" / "dual_quaternion".
const char* skinning_method_name(SkinningMethod method);

/// An affine map x ↦ linear · x + translation (m): the blended motion of one point.
struct PointMotion {
  Mat3 linear = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return linear * x + translation; }
};

/// The blended motion of every point of `weights` under the bone motions `bones`
/// (pose_skeleton). For DQS `linear` is a rotation. Throws std::invalid_argument when a
/// weighted bone has no motion in `bones`.
std::vector<PointMotion> blend_motions(const PointWeights& weights,
                                       const std::map<std::string, RigidMotion>& bones,
                                       SkinningMethod method);

/// `points` (n×3, m) moved each by its motion: row i ↦ motions[i].apply(row i).
Points3 apply_motions(const std::vector<PointMotion>& motions, const Points3& points);

}  // namespace tightfit
