#pragma once
/// The garment carried into a pose with its neutral embedding (paper Sec. 5.5): garment
/// vertex j stays at its surface point s_j and the body's control points move by their
/// skinning motions, Y_k = M_k y_k (body/posed_body.hpp), so
///   x_j = Σ_k L_k(s_j) Y_k     (the limit stencil of s_j over the posed control points).
/// Shared by the terms that look at the garment in other poses.
#include <string>
#include <vector>

#include "tightfit/body/skinning.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// One target pose: the skinning motion of every body vertex (n_b, blend_motions).
struct PoseMotions {
  std::string name;
  std::vector<PointMotion> motions;
};

/// Posed positions and limit-surface derivatives of every garment vertex.
struct PosedGarment {
  VecX x;                              ///< 3·n_g (m)
  std::vector<LimitWeights> stencils;  ///< per garment vertex
  Points3 xu, xv, xuu, xuv, xvv;       ///< n_g×3 parametric derivatives on the posed surface
};

/// Evaluates the garment of `embedding` on `surface` with the control points moved by
/// `motions` (one per body vertex; the first surface.num_control_vertices() are the
/// control points). Throws std::invalid_argument for sizes that do not match.
PosedGarment pose_garment(const LimitSurface& surface, const DesignEmbedding& embedding,
                          const std::vector<PointMotion>& motions);

/// Chain rule from ∂T/∂x (3·n_g, at the posed positions) to the embedded state:
/// d_s[2j..] += (x_u, x_v)ᵀ ∂T/∂x_j and d_y[3k..] += M_kᵀ Σ_j L_k(s_j) ∂T/∂x_j (M_k the
/// linear part of vertex k's motion).
void add_posed_position_gradient(const PosedGarment& posed, const std::vector<PointMotion>& motions,
                                 const VecX& d_x, VecX& d_s, VecX& d_y);

}  // namespace tightfit
