#pragma once
/// Records of a pattern optimization run: one entry per accepted L-BFGS iteration, the
/// L-BFGS memory, and the checkpoint that lets a run continue where it stopped.
#include <optional>
#include <string>
#include <vector>

#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/garment/pattern.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"

namespace tightfit {

/// A remeshing of degraded pieces after an accepted iteration (design/pattern_remesh.hpp).
/// The objective is evaluated again on the new meshes: its value may differ a little
/// from the iteration's (another discretization); the next iteration starts here.
struct RemeshRecord {
  std::vector<std::string> pieces;  ///< names of the remeshed pieces
  double value = 0.0;               ///< T on the remeshed pattern's equilibrium
  std::vector<double> term_values;  ///< w_j T_j there
  double gradient_norm = 0.0;       ///< ‖dT/dp‖₂ there
  int parameters = 0;               ///< design parameters after remeshing
  int garment_vertices = 0;         ///< after remeshing
  double min_angle_before = 0.0;    ///< degrees, over the remeshed pieces
  double min_angle_after = 0.0;     ///< degrees
  int newton_iterations = 0;        ///< of the equilibrium solve from the transferred state
  double seconds = 0.0;             ///< wall time of remeshing, transfer and re-solve (s)
  /// Non-empty when the remeshing failed and was undone (the run goes on with the old
  /// meshes; value, term_values, gradient_norm and counts are then the old ones).
  std::string failure;
};

/// A line search that met a discontinuity of the objective (design/snap_detector.hpp):
/// trials whose objective rose by about the same amount however much the step was
/// shortened, because the fit snapped to another equilibrium. Fields of the shortest
/// such trial.
struct SnapRecord {
  int trials = 0;                ///< trials that landed on the other equilibrium
  double rise = 0.0;             ///< T(trial) − T(accepted), units of T
  double step = 0.0;             ///< the trial's largest boundary-point move (m)
  double move = 0.0;             ///< largest garment-vertex displacement between the equilibria (m)
  int vertex = -1;               ///< that garment vertex
  Vec3 position = Vec3::Zero();  ///< where it was at the accepted equilibrium (m)
  std::string label;             ///< what it belongs to ("pieces 'front', 'back'")
};

/// One accepted iteration (iteration 0 is the initial pattern).
struct OptimizationIteration {
  int iteration = 0;
  double value = 0.0;               ///< T = Σ w_j T_j
  std::vector<double> term_values;  ///< w_j T_j, in the objective's entry order
  double gradient_norm = 0.0;       ///< ‖dT/dp‖₂ (units of T per m)
  double step_norm = 0.0;           ///< ‖Δp‖₂ (m) of the accepted step
  double max_point_move = 0.0;      ///< largest move of one boundary point (m)
  /// Largest point move (m) among this iteration's line-search trials whose forward solve
  /// converged (accepted or not): how far the equilibrium is known to follow a step. The
  /// next iteration's first trial is capped relative to it (PatternOptimizerOptions::
  /// step_growth). At least max_point_move.
  double max_solved_move = 0.0;
  double step_factor = 0.0;      ///< accepted line-search factor α
  int line_search_trials = 0;    ///< forward solves tried for this step
  int failed_solves = 0;         ///< of them: rejected patterns / unconverged solves
  int newton_iterations = 0;     ///< forward Newton iterations of this iteration
  int chord_steps = 0;           ///< of them: chord steps (no Hessian factorized)
  int force_accepted_steps = 0;  ///< of them: accepted by their force decrease, not the
                                 ///< energy (NewtonOptions::energy_precision)
  int factorizations = 0;        ///< Cholesky factorizations, forward and adjoint
  std::string adjoint_method;    ///< adjoint_method_name of the accepted gradient
  int krylov_iterations = 0;     ///< GMRES iterations of the accepted gradient
  double hessian_shift = 0.0;    ///< adjoint Hessian shift (0: exact gradient)
  double seconds = 0.0;          ///< wall time since the run started (s)
  /// Time split of this iteration (s), summed over its line-search trials: forward
  /// Newton solves, objective evaluations at the equilibria, and the gradient (term
  /// gradients, adjoint solve, pull-back).
  double seconds_forward = 0.0;
  double seconds_objective = 0.0;
  double seconds_adjoint = 0.0;
  /// Of seconds_forward: Hessian/gradient assembly and factorizations of Newton.
  double seconds_assembly = 0.0;
  double seconds_factorization = 0.0;
  std::optional<RemeshRecord> remesh;  ///< set when pieces were remeshed after this step
  std::optional<SnapRecord> snap;      ///< set when the line search met a snap-through
  /// The step of this iteration crossed a snap-through on purpose: after snaps stopped
  /// several line searches, the run accepted the shortest snapped trial (T rose by the
  /// jump) and went on from that equilibrium with an empty L-BFGS memory.
  bool jump = false;
};

/// L-BFGS curvature pairs, oldest first: s_k = p_{k+1} − p_k (m), y_k = ∇T_{k+1} − ∇T_k.
struct LbfgsMemory {
  std::vector<VecX> s;
  std::vector<VecX> y;
};

/// The design problem's pattern once pieces were remeshed (DesignProblem::remesh), as
/// far as it differs from the problem built from the scene: what a resumed run needs to
/// rebuild the garment, the biharmonic coordinates and the reference pattern exactly.
struct RemeshedDesign {
  /// The complete pattern with the reference rest positions Xbar0 (the rest shape at
  /// the last remeshing, which p0 and the reference areas come from).
  Pattern pattern;
  /// Per piece (n_k×2, m): the rest positions its current mesh was made with. Its
  /// biharmonic coordinates and its fresh-mesh quality are built from them.
  std::vector<Points2> mesh_rest;
};

/// Everything needed to continue a run: the accepted parameters and equilibrium, the
/// L-BFGS memory and the history so far, and the remeshed pattern when pieces were
/// remeshed.
/// Where the factorization the next forward solves start from was made (the held
/// factorization, adjoint_gradient.hpp): Newton's matrix at `state` with the rest
/// positions of `parameters`, shifted by `shift` (N/m at a DOF of mean stiffness). A
/// resumed run makes it again from these.
struct HeldFactorizationPoint {
  VecX parameters;      ///< p (m)
  EmbeddedState state;  ///< the state its Newton matrix was assembled at
  double shift = 0.0;   ///< diagonal shift δ (0: unshifted)
};

struct OptimizationCheckpoint {
  int iteration = 0;    ///< last accepted iteration
  VecX parameters;      ///< p (m)
  EmbeddedState state;  ///< equilibrium at p
  LbfgsMemory memory;   ///< on the current parameters (carried across remeshings)
  std::vector<OptimizationIteration> history;
  std::optional<RemeshedDesign> remeshed;  ///< set once a remeshing succeeded
  /// The ordering the held factorization of the accepted point was analysed with
  /// (DesignProblem::accepted_ordering; empty: its own search).
  CholeskyOrdering held_ordering;
  /// Where that factorization was made (absent in checkpoints of older versions: the
  /// resumed run then factorizes at the accepted point).
  std::optional<HeldFactorizationPoint> held_point;
};

}  // namespace tightfit
