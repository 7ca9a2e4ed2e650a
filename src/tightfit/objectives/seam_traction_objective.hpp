#pragma once
/// Seam traction objective (paper Sec. 5.4, Eq. 36): the total normal traction that the
/// cloth pulls on its seams with (physics/seam_traction.hpp),
///   T_seam = Σ_{i ∈ 𝒯} l0_i t (S_i n_i · n_i)        (N)
/// over every pair (seam edge, cloth triangle containing it) 𝒯, with l0_i the rest length
/// of the seam edge (m), n_i the unit rest-frame normal of that edge in its pattern
/// piece, t the cloth thickness (m) and S_i = 2 ∂W_cloth/∂C (Pa) the second Piola-Kirchhoff
/// stress of the relaxed StVK law in the element (C = FᵀF, F = Ds Dm⁻¹ in the piece's
/// rest frame). t S n·n is the normal traction per unit rest length of the seam (N/m).
/// As in the paper the traction itself (not its square) is summed; it is >= 0 for the
/// tension-only relaxed law, so minimizing it unloads the seams.
///
/// Depends on x and Xbar (through F, l0 and n). Derivatives by forward-mode automatic
/// differentiation per element, with S's derivative from the law's closed-form Hessian
/// in (I1, I2). C¹ in x and Xbar (the relaxed law is C²).
#include <memory>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/physics/seam_traction.hpp"

namespace tightfit {

class SeamTractionObjective : public DesignTerm {
 public:
  /// Collects, for both sides of every seam, each seam edge and the pattern triangle that
  /// contains it. `material` must be the simulated cloth's. Throws InputError (source
  /// "seam traction") when a seam edge is not an edge of any triangle.
  SeamTractionObjective(const Garment& garment, const ClothMaterial& material);

  std::string name() const override { return "seam traction"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }

  /// The seam-adjacent elements (physics/seam_traction.hpp), in the order of
  /// tractions().
  const std::vector<SeamElement>& elements() const { return elements_; }

  /// Normal traction t S n·n per unit rest length (N/m) of every seam element.
  VecX tractions(const DesignState& state) const;

 private:
  void check(const DesignState& state) const;

  std::shared_ptr<const GarmentTopology> topology_;
  int num_garment_ = 0;
  int num_pattern_ = 0;
  FabricLaw law_;
  std::vector<SeamElement> elements_;
};

}  // namespace tightfit
