#include "tightfit/body/posed_body.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

/// Growth of a tet's volume beyond which a pose "pulls the body apart": rigid skinning
/// motions keep volumes; more than threefold only comes from weights that tear.
constexpr double kMaxTetGrowth = 3.0;

}  // namespace

VecX tet_volumes(const Body& body, const Points3& y) {
  const Tetrahedra& t = body.volume.tets;
  VecX v(t.rows());
  for (Eigen::Index e = 0; e < t.rows(); ++e) {
    const Vec3 a = y.row(t(e, 0)).transpose();
    const Vec3 b = y.row(t(e, 1)).transpose() - a, c = y.row(t(e, 2)).transpose() - a,
               d = y.row(t(e, 3)).transpose() - a;
    v[e] = b.dot(c.cross(d)) / 6.0;
  }
  return v;
}

PosedBody pose_body(const Body& body, const Points3& y, const PointWeights& weights,
                    const std::map<std::string, RigidMotion>& bones, SkinningMethod method) {
  if (y.rows() != body.num_vertices() || weights.num_points() != body.num_vertices())
    throw std::invalid_argument(
        "pose_body: one position and one weight row per body vertex expected");
  PosedBody out;
  out.motions = blend_motions(weights, bones, method);
  out.positions = apply_motions(out.motions, y);
  const VecX before = tet_volumes(body, y), after = tet_volumes(body, out.positions);
  out.min_volume_ratio = std::numeric_limits<double>::infinity();
  out.max_volume_ratio = -std::numeric_limits<double>::infinity();
  for (Eigen::Index e = 0; e < before.size(); ++e) {
    if (!(after[e] > 0.0)) ++out.inverted_tets;
    const double ratio = after[e] / before[e];
    if (ratio < out.min_volume_ratio) {
      out.min_volume_ratio = ratio;
      out.worst_tet = static_cast<int>(e);
    }
    out.max_volume_ratio = std::max(out.max_volume_ratio, ratio);
  }
  if (before.size() == 0) out.min_volume_ratio = out.max_volume_ratio = 1.0;
  out.volume_ratio = after.sum() / before.sum();
  return out;
}

void check_posed_body(const PosedBody& posed, const Body& body, const std::string& pose_name,
                      const std::string& source) {
  if (posed.inverted_tets > 0) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 4; ++k)
      c += body.volume.vertices.row(body.volume.tets(posed.worst_tet, k)).transpose() / 4.0;
    char where[96];
    std::snprintf(where, sizeof where, "(%.3f, %.3f, %.3f) m", c.x(), c.y(), c.z());
    throw InputError(source,
                     "pose \"" + pose_name + "\" inverts " + std::to_string(posed.inverted_tets) +
                         " of the body's " + std::to_string(body.volume.num_tets()) +
                         " tets, the worst at " + where +
                         " in the neutral body (a joint bent beyond what skinning can follow?)");
  }
  if (posed.max_volume_ratio > kMaxTetGrowth)
    throw InputError(source, "pose \"" + pose_name + "\" pulls the body apart: a tet grows to " +
                                 std::to_string(posed.max_volume_ratio) + " times its volume");
  if (!posed.positions.allFinite())
    throw InputError(source, "pose \"" + pose_name + "\" gives non-finite body positions");
}

}  // namespace tightfit
