#pragma once
/// Traction-free pinned boundaries (paper Sec. 4.1, Eq. 27): the tangential force that
/// the pins of the pinned garment vertices F (cuffs, waistbands) hold,
///   R_fixed = Σ_{i ∈ F} w_i ‖P_i ∂U_g/∂x_i‖²,   P_i = I − n_i n_iᵀ      (N²),
/// with w_i the reference mesh's mean boundary edge over the vertex's share of the pinned
/// rim's rest length (objectives/resolution.hpp: about 1 on the design's initial mesh; a
/// pin holds the traction along its share, so the weighted sum is the same on any mesh),
/// U_g the garment's elastic energy (cloth and seam springs) at the equilibrium and n_i
/// the limit-surface normal there. The paper writes ‖dU/ds_i‖², the force in the face's
/// (u, v) coordinates; its size then depends on each face's parametrization, so this
/// term measures the same force in newtons in the tangent plane instead (the normal part
/// is carried by the body, the tangential part by the pin: a pattern whose pinned rims
/// sit in equilibrium by themselves needs no pin to hold them).
///
/// Depends on x and Xbar through the forces and on the body state through the normals
/// (add_embedding_gradient). Gradient: ∂/∂x = H a, ∂/∂Xbar = (∂²U/∂x∂Xbar)ᵀ a with
/// a_i = 2 P_i g_i, and ∂/∂n_i = −2 (n_i·g_i) g_i carried to y through the limit
/// stencils' derivatives.
#include <memory>
#include <string>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/resolution.hpp"
#include "tightfit/physics/garment_energies.hpp"
#include "tightfit/solve/garment_simulation.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

class PinnedTractionRegularizer : public DesignTerm {
 public:
  /// The garment's energies are rebuilt from `materials` as the simulation builds them;
  /// `surface` must outlive the term. `reference`: the resolution of the weights w_i
  /// (the garment's own when not known). Throws InputError (source "pinned traction")
  /// for a garment without pinned vertices.
  PinnedTractionRegularizer(const Garment& garment, const SimulationMaterials& materials,
                            const LimitSurface& surface, const ResolutionReference& reference = {});
  ~PinnedTractionRegularizer() override;

  std::string name() const override { return "pinned traction"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }
  bool depends_on_embedding() const override { return true; }
  /// Adds ∂T/∂y only: the pinned vertices' surface points are fixed (no DOF).
  void add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const override;

 private:
  struct Evaluation;
  Evaluation evaluate(const DesignState& state) const;

  /// The garment's cloth and seam energies reading `rest` (which must outlive them).
  GarmentEnergies energies_at(const Points2& rest) const;

  const LimitSurface& surface_;
  std::vector<int> pinned_;
  // The garment energies' connectivity and materials; energies_at binds them to a state's rest.
  std::shared_ptr<const GarmentTopology> topology_;
  ClothMaterial fabric_;
  SeamMaterial seam_;
  std::vector<double> weights_;  ///< w_i per entry of pinned_
};

}  // namespace tightfit
