#pragma once
/// The body in a pose (paper Sec. 5.5: the target poses y_1 … y_n).
///
/// Definition used throughout tightfit: pose i of a body state y (n×3, the neutral
/// equilibrium with the garment on, or the rest body) is
///   y_i(v) = M_i(v) y(v),
/// each vertex moved by the blended skinning motion M_i(v) of its weights
/// (skinning.hpp; a rigid motion per vertex with dual quaternions). So the indentation
/// the garment made in the neutral pose moves with the tissue; the body is not solved
/// again in the pose, and the garment keeps its neutral embedding s0 (its positions in pose
/// i are x(s0, y_i)), as in the paper. Consequences: the posed body has the neutral
/// pose's stresses, not its own equilibrium; a pose is as good as its skinning (DQS keeps
/// the volume at bent joints; skin sliding over bone, muscle bulging and soft-tissue
/// contact at deep flexion are not modelled). Because y_i is linear in y for fixed
/// weights, dy_i/dy = M_i(v) per vertex: the design gradient through a pose needs no
/// extra solve.
#include <map>
#include <string>
#include <vector>

#include "tightfit/body/body.hpp"
#include "tightfit/body/skinning.hpp"

namespace tightfit {

/// A posed body and how its tets came through.
struct PosedBody {
  Points3 positions;                 ///< y_i, n×3 (m)
  std::vector<PointMotion> motions;  ///< M_i(v) per body vertex
  int inverted_tets = 0;             ///< tets with volume <= 0 in the pose
  double min_volume_ratio = 1.0;     ///< smallest posed / neutral tet volume
  int worst_tet = -1;                ///< the tet of min_volume_ratio (−1: no tets)
  double max_volume_ratio = 1.0;     ///< largest posed / neutral tet volume
  double volume_ratio = 1.0;         ///< posed / neutral volume of the whole body
};

/// Poses the body state `y` (n×3, body.num_vertices() rows) with the bone motions
/// `bones` (pose_skeleton) and the weights of every body vertex (body_skin_weights).
/// Throws std::invalid_argument for sizes that do not match.
PosedBody pose_body(const Body& body, const Points3& y, const PointWeights& weights,
                    const std::map<std::string, RigidMotion>& bones, SkinningMethod method);

/// Throws InputError (source `source`) when the pose inverts a tet (naming the pose
/// and how many of the body's tets it inverted) or grows one beyond three times its
/// volume (it pulls the body apart).
void check_posed_body(const PosedBody& posed, const Body& body, const std::string& pose_name,
                      const std::string& source);

/// Signed volume (m³) of every tet of `body` at positions `y`.
VecX tet_volumes(const Body& body, const Points3& y);

}  // namespace tightfit
