#pragma once
/// Pressure objective (paper Sec. 5.3, Eq. 31-35) with a pressure RANGE per element:
///   T_pressure = Σ_e A_e pen_e(p_e),
///   pen_e(p) = (p − p_min,e)² for p < p_min,e,  (p − p_max,e)² for p > p_max,e,  0 between,
/// (p_min = p_max = p̂ gives Eq. 34 exactly), A_e the rest area (m²), so T is in Pa²·m².
/// With pressure regions (pressure_regions.hpp) the ranges come from the regions and
/// their membership weights w_{r,e}(x), and the objective sums them:
///   T_pressure = Σ_r Σ_e A_e w_{r,e}(x) pen_r(p_e);
/// a triangle in no region contributes nothing.
///
/// Pressure per element (generalized Young-Laplace, Eq. 31, as in cloth_analysis.hpp):
///   p_e = t tr(σ_e Λ_e),   σ_e = F S Fᵀ / J,   S = 2 ∂W/∂C (relaxed StVK),  J = √det C,
/// in Pa, positive when the fabric presses onto a convex body (outward-oriented garment
/// faces). Λ_e is the mid-edge shape operator of Grinspun et al. 2006 on the welded
/// garment mesh (Eq. 32-33), computed by physics/mid_edge_shape_operator (its per-face
/// kernel physics/mid_edge_kernel.hpp, its edge topology physics/mid_edge_topology.hpp):
///   Λ_f = Σ_i (θ_i/2 + s_i φ_i) (l_i/A_f) t_i t_iᵀ,   φ = argmin Σ_f A_f tr(Λ_f²);
/// σ_e and p_e come from the kernel physics/element_pressure.hpp, as in the fit analysis.
///
/// Gradient: EXACT, including the dependence of the edge unknowns φ on x (Eq. 35) by one
/// extra adjoint solve with the same matrix K as the φ system (K μ = ∂T/∂φ):
///   dT/dx = ∂T/∂x|_φ − ∂/∂x [Σ_f A_f tr(Λ_f(x; φ) Γ_f(x; μ))]|_{φ,μ},
///   Γ_f = Σ_i s_i μ_i (l_i/A_f) t_i t_iᵀ,
/// since the φ system is r(φ, x) = Σ_f A_f G_fᵀ vec Λ_f = 0. Per-face partial
/// derivatives (through face normals, dihedral angles, edge lengths, F and S) come from
/// forward-mode automatic differentiation (Eigen AutoDiff) of the same kernels; S's
/// derivative uses the law's closed-form Hessian in (I1, I2). ∂T/∂Xbar goes through F, S, J and A_e
/// (Λ does not depend on Xbar). T is C¹ (the relaxed law is C²).
#include <memory>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/pressure_regions.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/physics/mid_edge_topology.hpp"

namespace tightfit {

class PressureObjective : public DesignTerm {
 public:
  /// Per-element range [min_pressure[e], max_pressure[e]] (Pa), one entry per garment
  /// triangle. `material` must be the simulated cloth's. Throws InputError (source
  /// "pressure objective") for wrong sizes, non-finite or inverted ranges, and for a
  /// garment mesh that is non-manifold or inconsistently oriented.
  PressureObjective(const Garment& garment, const ClothMaterial& material, VecX min_pressure,
                    VecX max_pressure);
  /// The same range [min_pressure, max_pressure] (Pa) on every element.
  PressureObjective(const Garment& garment, const ClothMaterial& material, double min_pressure,
                    double max_pressure);
  /// The ranges of `regions` (resolved on this garment), summed where they overlap.
  PressureObjective(const Garment& garment, const ClothMaterial& material, PressureRegions regions);

  std::string name() const override { return "pressure"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }

  /// p_e (Pa) for every garment triangle at the state. Throws SolverError for a
  /// degenerate deformed triangle.
  VecX pressures(const DesignState& state) const;
  /// Λ_e (3×3, 1/m, world frame) for every garment triangle at positions x.
  std::vector<Mat3> shape_operators(const VecX& x) const;

 private:
  void check(const DesignState& state) const;

  Triangles pattern_triangles_;
  Triangles garment_triangles_;
  int num_garment_ = 0;
  int num_pattern_ = 0;
  FabricLaw law_;
  // Per-element range (±infinity where the regions give the targets) and the regions.
  VecX min_pressure_;
  VecX max_pressure_;
  PressureRegions regions_;
  // Edge unknowns, signs and vertices across of the mid-edge system (shared by copies).
  std::shared_ptr<const MidEdgeTopology> topology_;
};

}  // namespace tightfit
