#include "tightfit/body/bvh_pose.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "tightfit/common/error.hpp"

namespace tightfit {

BvhFrameFit fit_bvh_frame(const BvhMotion& motion,
                          const std::map<std::string, BoneSegment>& skeleton) {
  std::vector<Vec3> rest(motion.joints.size());
  BvhFrameFit fit;
  Eigen::Matrix3Xd from(3, 0), to(3, 0);
  std::vector<std::pair<Vec3, Vec3>> pairs;
  for (std::size_t j = 0; j < motion.joints.size(); ++j) {
    const BvhJoint& joint = motion.joints[j];
    rest[j] = joint.offset +
              (joint.parent >= 0 ? rest[static_cast<std::size_t>(joint.parent)] : Vec3::Zero());
    const auto bone = skeleton.find(joint.name);
    if (bone == skeleton.end()) {
      fit.unmatched_joints.push_back(joint.name);
      continue;
    }
    pairs.emplace_back(rest[j], bone->second.head);
  }
  if (pairs.size() < 3 || 2 * fit.unmatched_joints.size() > motion.joints.size()) {
    std::string names;
    for (std::size_t k = 0; k < std::min<std::size_t>(5, fit.unmatched_joints.size()); ++k)
      names += (k ? ", \"" : "\"") + fit.unmatched_joints[k] + "\"";
    throw InputError(motion.source, std::to_string(fit.unmatched_joints.size()) + " of the BVH's " +
                                        std::to_string(motion.joints.size()) +
                                        " joints are not bones of the skeleton (" + names +
                                        (fit.unmatched_joints.size() > 5 ? ", ..." : "") +
                                        "): a motion of another skeleton");
  }
  from.resize(3, static_cast<Eigen::Index>(pairs.size()));
  to.resize(3, static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    from.col(static_cast<Eigen::Index>(k)) = pairs[k].first;
    to.col(static_cast<Eigen::Index>(k)) = pairs[k].second;
  }
  const Eigen::Matrix4d T = Eigen::umeyama(from, to, true);
  fit.scale = T.block<3, 3>(0, 0).col(0).norm();
  if (!(fit.scale > 0.0) || !T.allFinite())
    throw InputError(motion.source, "the BVH's rest joints are degenerate (all in one place?)");
  fit.rotation = T.block<3, 3>(0, 0) / fit.scale;
  fit.translation = T.block<3, 1>(0, 3);
  fit.common_joints = static_cast<int>(pairs.size());
  Vec3 lo = to.rowwise().minCoeff(), hi = to.rowwise().maxCoeff();
  double sum2 = 0.0;
  for (Eigen::Index k = 0; k < from.cols(); ++k) {
    const double r = (fit.scale * fit.rotation * from.col(k) + fit.translation - to.col(k)).norm();
    fit.max_residual = std::max(fit.max_residual, r);
    sum2 += r * r;
  }
  fit.rms_residual = std::sqrt(sum2 / static_cast<double>(from.cols()));
  const double size = (hi - lo).norm();
  if (fit.max_residual > 0.05 * size)
    throw InputError(motion.source,
                     "the BVH's rest skeleton does not match the body's skeleton: after the best "
                     "fit a joint is " +
                         std::to_string(fit.max_residual) + " m from its bone (" +
                         std::to_string(100.0 * fit.max_residual / size) +
                         " % of the skeleton's size)");
  return fit;
}

BoneRotations bvh_pose(const BvhMotion& motion, int frame, const BvhFrameFit& fit,
                       std::vector<std::string>* ignored) {
  if (frame < 0 || frame >= motion.num_frames())
    throw InputError(motion.source,
                     "frame " + std::to_string(frame) + " does not exist (the file has " +
                         std::to_string(motion.num_frames()) + " frames, counted from 0)");
  BoneRotations out;
  for (std::size_t j = 0; j < motion.joints.size(); ++j) {
    const Mat3 R = motion.local_rotation(static_cast<int>(j), frame);
    if ((R - Mat3::Identity()).norm() == 0.0) continue;
    const std::string& name = motion.joints[j].name;
    if (std::find(fit.unmatched_joints.begin(), fit.unmatched_joints.end(), name) !=
        fit.unmatched_joints.end()) {
      const double angle = Eigen::AngleAxisd(R).angle();
      if (ignored && angle > EIGEN_PI / 180.0) ignored->push_back(name);
      continue;
    }
    out[motion.joints[j].name] = fit.rotation * R * fit.rotation.transpose();
  }
  return out;
}

}  // namespace tightfit
