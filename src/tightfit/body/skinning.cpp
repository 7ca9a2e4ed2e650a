#include "tightfit/body/skinning.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

namespace tightfit {

void PointWeights::add_point(const std::vector<std::pair<int, double>>& entries) {
  double total = 0.0;
  for (const auto& [b, w] : entries)
    if (w > 0.0) total += w;
  if (!(total > 0.0)) throw std::invalid_argument("PointWeights::add_point: no positive weight");
  for (const auto& [b, w] : entries) {
    if (!(w > 0.0)) continue;
    bone.push_back(b);
    weight.push_back(w / total);
  }
  offsets.push_back(static_cast<int>(bone.size()));
}

VecX PointWeights::summed(const std::vector<std::string>& names) const {
  std::vector<char> selected(bones.size(), 0);
  for (std::size_t b = 0; b < bones.size(); ++b)
    for (const std::string& name : names) selected[b] |= bones[b] == name;
  VecX s = VecX::Zero(num_points());
  for (int i = 0; i < num_points(); ++i)
    for (int k = offsets[i]; k < offsets[i + 1]; ++k)
      if (selected[bone[k]]) s[i] += weight[k];
  return s;
}

const char* skinning_method_name(SkinningMethod method) {
  return method == SkinningMethod::kLinearBlend ? "linear_blend" : "dual_quaternion";
}

namespace {

/// A unit dual quaternion q_r + ε q_d of a rigid motion: q_d = ½ t q_r.
struct DualQuaternion {
  Eigen::Quaterniond real;
  Eigen::Quaterniond dual;
};

DualQuaternion to_dual_quaternion(const RigidMotion& m) {
  Eigen::Quaterniond r(m.rotation);
  r.normalize();
  const Eigen::Quaterniond t(0.0, m.translation.x(), m.translation.y(), m.translation.z());
  Eigen::Quaterniond d = t * r;
  d.coeffs() *= 0.5;
  return {r, d};
}

/// The rigid motion of the normalized blend b = Σ w_k ± dq_k (Kavan et al. 2008, Alg. 1):
/// rotation of b_r/‖b_r‖, translation 2 (w_r v_d − w_d v_r + v_r × v_d)/‖b_r‖².
PointMotion from_blend(const Eigen::Vector4d& real, const Eigen::Vector4d& dual) {
  const double n = real.norm();
  const Eigen::Quaterniond r(real[3] / n, real[0] / n, real[1] / n,
                             real[2] / n);  // coeffs: x y z w
  const Vec3 vr = real.head<3>() / n, vd = dual.head<3>() / n;
  const double wr = real[3] / n, wd = dual[3] / n;
  return {r.toRotationMatrix(), 2.0 * (wr * vd - wd * vr + vr.cross(vd))};
}

}  // namespace

std::vector<PointMotion> blend_motions(const PointWeights& weights,
                                       const std::map<std::string, RigidMotion>& bones,
                                       SkinningMethod method) {
  std::vector<const RigidMotion*> motion(weights.bones.size());
  std::vector<DualQuaternion> dq(weights.bones.size());
  for (std::size_t b = 0; b < weights.bones.size(); ++b) {
    const auto it = bones.find(weights.bones[b]);
    if (it == bones.end())
      throw std::invalid_argument("blend_motions: no motion for bone " + weights.bones[b]);
    motion[b] = &it->second;
    dq[b] = to_dual_quaternion(it->second);
  }
  std::vector<PointMotion> out(static_cast<std::size_t>(weights.num_points()));
  for (int i = 0; i < weights.num_points(); ++i) {
    const int begin = weights.offsets[i], end = weights.offsets[i + 1];
    if (method == SkinningMethod::kLinearBlend) {
      PointMotion m{Mat3::Zero(), Vec3::Zero()};
      for (int k = begin; k < end; ++k) {
        m.linear += weights.weight[k] * motion[weights.bone[k]]->rotation;
        m.translation += weights.weight[k] * motion[weights.bone[k]]->translation;
      }
      out[i] = m;
      continue;
    }
    // Antipodality: every quaternion on the hemisphere of the heaviest bone's.
    int heaviest = begin;
    for (int k = begin; k < end; ++k)
      if (weights.weight[k] > weights.weight[heaviest]) heaviest = k;
    const Eigen::Vector4d pivot = dq[weights.bone[heaviest]].real.coeffs();
    Eigen::Vector4d real = Eigen::Vector4d::Zero(), dual = Eigen::Vector4d::Zero();
    for (int k = begin; k < end; ++k) {
      const DualQuaternion& q = dq[weights.bone[k]];
      const double sign = q.real.coeffs().dot(pivot) < 0.0 ? -1.0 : 1.0;
      real += sign * weights.weight[k] * q.real.coeffs();
      dual += sign * weights.weight[k] * q.dual.coeffs();
    }
    out[i] = from_blend(real, dual);
  }
  return out;
}

Points3 apply_motions(const std::vector<PointMotion>& motions, const Points3& points) {
  if (static_cast<Eigen::Index>(motions.size()) != points.rows())
    throw std::invalid_argument("apply_motions: one motion per point expected");
  Points3 out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out.row(i) = motions[static_cast<std::size_t>(i)].apply(points.row(i).transpose()).transpose();
  return out;
}

}  // namespace tightfit
