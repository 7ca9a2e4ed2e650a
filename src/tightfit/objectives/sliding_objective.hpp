#pragma once
/// Sliding objective over a range of motion (paper Sec. 5.5, Eq. 37-38).
///
/// The garment keeps its neutral embedding s0 (garment vertex j at surface point s_j) and
/// is carried into pose i by the posed body Y_i (body/posed_body.hpp: body vertex k at
/// M_ik y_k, M_ik its skinning motion): x_ij = x(s_j; Y_i) on the posed limit surface.
/// There the cloth is generally not in equilibrium; the elastic force on vertex j,
///   f_ij = −∂U_g/∂x_j (x_i, Xbar)     (U_g: cloth + seam springs; N),
/// splits into the force pressing on the body f_n = −f·n_ij (n_ij the outward normal of
/// the posed limit surface: a taut garment pulls its vertices inwards, and the body holds
/// them) and a tangential magnitude f_t = ‖f − (f·n) n‖. Coulomb friction with
/// coefficient μ holds up to f_c = μ max(f_n, 0) (only fabric pressing on the body gives
/// friction; the paper's f_c = μ f·n with f the force on the body); what exceeds it would
/// slide:
///   T_slide = Σ_i Σ_j w_j T_ij²,   T_ij = max(f_t − f_c, 0)      (N²),
/// over the free (unpinned) garment vertices (the pinned ones are held by their pins),
/// with vertex weights w_j (sliding_vertex_weights: about 1 on the design's initial mesh)
/// that keep T the same when a remeshing changes the vertices' areas.
///
/// Gradient (Eq. 38): T depends on the design through Xbar (the forces' rest shape:
/// ∂T/∂Xbar = −Σ_i (∂²U/∂x∂Xbar)ᵀ a_i with a_i = ∂T/∂f_i) and on the neutral equilibrium
/// (s0, y) through x_i and n_i; add_embedding_gradient gives ∂T/∂s and ∂T/∂y, which the
/// adjoint solve turns into the sensitivity through s0 and y (Eq. 38's
/// (∂x_i/∂s0 ∂s0/∂p)ᵀ ∂T/∂x_i, plus the body's own sensitivity, which the paper's
/// formula leaves out). Second derivatives of the limit surface give ∂n/∂s, the exact
/// cloth Hessian gives ∂f/∂x. T is C¹ away from f_n = 0 (where the friction limit has a
/// kink); the squared hinge is C¹ at f_t = f_c.
#include <memory>
#include <string>
#include <vector>

#include "tightfit/body/skinning.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/posed_garment.hpp"
#include "tightfit/objectives/resolution.hpp"
#include "tightfit/physics/garment_energies.hpp"
#include "tightfit/solve/garment_simulation.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// Per garment vertex in one pose: the forces of the sliding objective.
struct SlidingForces {
  VecX normal;      ///< f_n (N), positive pressing on the body
  VecX tangential;  ///< f_t (N)
  VecX excess;      ///< T_ij = max(f_t − f_c, 0) (N); 0 for pinned vertices
};

class SlidingObjective : public DesignTerm {
 public:
  /// `surface` is the body's limit surface (must outlive the term), `num_body_vertices`
  /// n_b, `poses` at least one, each with n_b motions; `friction` μ ≥ 0. The garment's
  /// energies are rebuilt here from `materials` exactly as the simulation builds them.
  /// Throws InputError (source "sliding objective") for a negative or non-finite μ, no
  /// poses, or motions of the wrong count. `weights`: w_j per garment vertex
  /// (sliding_vertex_weights; empty: 1 each), std::invalid_argument when of the wrong
  /// size, negative or not finite.
  SlidingObjective(const Garment& garment, const SimulationMaterials& materials,
                   const LimitSurface& surface, int num_body_vertices,
                   std::vector<PoseMotions> poses, double friction, VecX weights = {});
  ~SlidingObjective() override;

  std::string name() const override { return "sliding"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }
  bool depends_on_embedding() const override { return true; }
  void add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const override;

  const std::vector<PoseMotions>& poses() const { return poses_; }
  double friction() const { return friction_; }
  /// Pose `pose` at the state, for reports: its forces and the garment carried there.
  struct PoseView {
    SlidingForces forces;
    PosedGarment garment;
  };
  PoseView pose_view(const DesignState& state, int pose) const;

 private:
  struct PoseEvaluation;
  /// Pose `pose` at `state`, with the garment energies bound to state.rest (built once
  /// per call of the public methods, shared by all poses).
  PoseEvaluation evaluate(const DesignState& state, const GarmentEnergies& energies, int pose,
                          bool with_gradient) const;

  /// The garment's cloth and seam energies reading `rest` (which must outlive them).
  GarmentEnergies energies_at(const Points2& rest) const;

  const LimitSurface& surface_;
  int num_garment_ = 0;
  int num_body_ = 0;
  std::vector<char> pinned_;
  std::vector<PoseMotions> poses_;
  double friction_ = 0.3;
  // The garment energies' connectivity and materials; energies_at binds them to a state's rest.
  std::shared_ptr<const GarmentTopology> topology_;
  ClothMaterial fabric_;
  SeamMaterial seam_;
  VecX weights_;
};

/// w_j of every garment vertex of `garment`: `reference`'s rest area per vertex over the
/// vertex's share of the rest area (garment_vertex_areas; the garment's own per-vertex
/// area when `reference` is not known). A vertex's force grows with its area, so T_ij²
/// w_j is its area times the squared excess traction over the reference area: T is the
/// same on any mesh of the same fit.
VecX sliding_vertex_weights(const Garment& garment, const ResolutionReference& reference);

}  // namespace tightfit
