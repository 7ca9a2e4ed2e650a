#pragma once
/// A design term evaluated in the neutral pose AND in every given pose (beyond the
/// paper; the scene's `"poses": "all"` on stretch, directional stretch and pressure):
///   T = T_inner(x, Xbar) + Σ_i T_inner(x_i, Xbar),
/// x_i the garment carried into pose i with its neutral embedding (posed_garment.hpp),
/// so that a garment is designed to stay within its stretch or pressure range over the
/// whole motion, not just standing. The inner term must be a function of x and Xbar
/// only (not of the embedding). Gradient: the inner term's ∂/∂Xbar at every pose, and
/// its ∂/∂x_i carried to the embedded state (s, y) through the posed stencils and the
/// skinning motions (add_embedding_gradient), which the adjoint solve takes on.
#include <memory>
#include <string>
#include <vector>

#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/posed_garment.hpp"

namespace tightfit {

class AllPosesTerm : public DesignTerm {
 public:
  /// `surface` must outlive the term. Throws InputError (source "poses") for no poses
  /// or an inner term that depends on the embedding itself.
  AllPosesTerm(std::shared_ptr<const DesignTerm> inner, const LimitSurface& surface,
               std::vector<PoseMotions> poses);

  std::string name() const override { return inner_->name() + " (all poses)"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }
  bool depends_on_embedding() const override { return true; }
  void add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const override;

  /// The inner term's value in pose `pose` alone (for reports).
  double pose_value(const DesignState& state, int pose) const;
  const std::vector<PoseMotions>& poses() const { return poses_; }

 private:
  PosedGarment posed(const DesignState& state, int pose) const;

  std::shared_ptr<const DesignTerm> inner_;
  const LimitSurface& surface_;
  std::vector<PoseMotions> poses_;
};

}  // namespace tightfit
