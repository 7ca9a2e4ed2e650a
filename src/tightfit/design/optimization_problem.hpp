#pragma once
/// The reduced design problem of paper Eq. 21: minimize T(x(q(p)), Xbar(p)) over the
/// design parameters p, the 2D positions (m) of every piece's boundary vertices in
/// BiharmonicCoordinates' layout. The rest positions follow as
///   Xbar(p) = Xbar0 + W (p − p0)
/// (Xbar0, p0: the initial pattern): the paper's Xbar = W p applied to the boundary
/// DISPLACEMENT, so the mesher's interior vertices are kept at p0 instead of jumping to
/// their biharmonic positions; dXbar/dp = W either way, and both agree for affine
/// boundary changes (W reproduces affine maps).
///
/// Evaluating at p sets the simulation's rest positions to W p and solves for the
/// equilibrium, warm-started from the last ACCEPTED equilibrium (never from a rejected
/// trial). Newton's first steps there are chord steps with the factorization held for
/// the accepted point (AdjointSolver::held_factorization: the accepted trial's last
/// Newton factorization, or one made at an earlier point or at the equilibrium when
/// the adjoint needed it): the first one is the first-order prediction
/// Δq = −H⁻¹ (∂g/∂p) Δp of the new equilibrium, and while the chord steps contract fast
/// the forward solve needs no factorization of its own. Everything a trial starts from
/// is a function of the accepted point and of where its held factorization was made
/// (accepted_held_point(), stored in the checkpoint), so a resumed run repeats an
/// uninterrupted one exactly. The gradient comes from
/// the adjoint (adjoint_gradient.hpp) and the biharmonic pull-back, dT/dp = Wᵀ dT/dXbar. A trial
/// fails, without throwing, when
///  * a rest triangle flips or shrinks below `min_area_ratio` of its initial area,
///  * the rest-dependent energies reject the rest shape (InputError),
///  * the forward Newton solve does not converge (SolverError or report),
///  * the equilibrium, T or its gradient is not finite;
/// the optimizer then backtracks. After a failure the simulation holds an unspecified
/// state until the next evaluate() or restore_accepted().
///
/// Remeshing (remesh(), pattern_remesh.hpp). When a piece's accepted rest mesh degrades
/// (degraded_pieces()), remesh() replaces the garment by a remeshed one with the
/// embedding transferred, rebuilds the simulation's energies, the objective (through
/// the ObjectiveFactory: terms hold index sets of one topology) and the biharmonic
/// coordinates (pieces left unchanged keep theirs), builds a new reference from the
/// remeshed pattern (initial rest positions, parameters and areas, coordinates,
/// objective, fresh-mesh qualities) and solves the equilibrium from the transferred
/// state against it. The new reference is swapped in only when all of that succeeded;
/// otherwise the old garment is put back at the accepted point and nothing else changed. A remeshed
/// pattern or transferred state holding a NaN or infinity is a SolverError instead
/// (finite_state.hpp): the run ends there, nothing is changed.
/// remeshed_design() describes the result for a checkpoint, and restore_remeshed_design()
/// puts a problem built from the scene back into that remeshed state (--resume).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tightfit/design/adjoint_gradient.hpp"
#include "tightfit/design/biharmonic_coordinates.hpp"
#include "tightfit/design/optimization_state.hpp"
#include "tightfit/design/pattern_remesh.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

struct DesignProblemOptions {
  /// A trial pattern is rejected when a rest triangle's signed area falls below this
  /// fraction of its initial signed area (a flipped triangle has a negative ratio).
  double min_area_ratio = 0.05;
  /// Forward solves reuse each Newton step's factorization for chord steps while they
  /// contract fast (ChordSteps::reuse_own); the equilibrium is the same to the tolerance.
  bool reuse_factorizations = true;
  AdjointOptions adjoint;
  PatternRemeshOptions remesh;
};

/// Builds the design objective for the simulation's current garment (called again
/// after every remeshing; must return the same terms in the same order).
using ObjectiveFactory =
    std::function<std::shared_ptr<const DesignTermSum>(const GarmentSimulation&)>;

/// One evaluation of the design problem at parameters p.
struct DesignEvaluation {
  bool ok = false;                  ///< converged equilibrium, valid pattern, finite T
  std::string failure;              ///< why not (empty when ok)
  double value = 0.0;               ///< T = Σ w_j T_j (only when ok)
  std::vector<double> term_values;  ///< w_j T_j per objective entry (only when ok)
  VecX gradient;                    ///< dT/dp (only when ok and requested)
  double hessian_shift = 0.0;       ///< adjoint Hessian shift (0: exact gradient)
  double adjoint_residual = 0.0;    ///< relative residual of the adjoint solve
  int newton_iterations = 0;        ///< of the forward solve (chord steps included)
  int chord_steps = 0;              ///< of them: chord steps from the held factorization
  int force_accepted_steps = 0;     ///< of them: accepted by their force decrease
                                    ///< (NewtonOptions::energy_precision)
  int factorizations = 0;           ///< Cholesky factorizations of the forward solve
  int adjoint_factorizations = 0;   ///< and of the gradient
  AdjointMethod adjoint_method = AdjointMethod::kNone;
  int krylov_iterations = 0;    ///< GMRES iterations of the adjoint solve
  double force_residual = 0.0;  ///< N, final force norm of the forward solve
  /// How far the equilibrium moved from the accepted one (m): the largest displacement of
  /// a garment vertex, which one, where it was (m) and what it belongs to ("piece 'front'").
  /// A step that makes the fit snap to another equilibrium moves it far (PatternOptimizer).
  double equilibrium_move = 0.0;
  int moved_vertex = -1;
  Vec3 moved_vertex_position = Vec3::Zero();
  std::string moved_vertex_label;
  double seconds_assembly = 0.0;       ///< of seconds_forward: gradients and Hessians (s)
  double seconds_factorization = 0.0;  ///< of seconds_forward: Cholesky factorizations (s)
  double seconds_forward = 0.0;        ///< forward Newton solve (s)
  double seconds_objective = 0.0;      ///< evaluating T at the equilibrium (s)
  double seconds_adjoint = 0.0;        ///< dT/dp: term gradients, adjoint solve, pull-back (s)
};

/// What one remeshing did.
struct RemeshOutcome {
  bool ok = false;
  std::string failure;            ///< why it was undone (when !ok)
  std::vector<int> pieces;        ///< remeshed pieces (the degraded ones and their seam partners)
  double min_angle_before = 0.0;  ///< degrees, smallest angle over those pieces before
  double min_angle_after = 0.0;   ///< and after remeshing
  int parameters_before = 0;
  int parameters_after = 0;
  int garment_vertices_before = 0;
  int garment_vertices_after = 0;
  int triangles_after = 0;      ///< pattern triangles of the new garment
  double seconds = 0.0;         ///< wall time of remeshing, transfer and re-solve (s)
  DesignEvaluation evaluation;  ///< at the remeshed pattern, with gradient (when ok)
};

class DesignProblem {
 public:
  /// `sim` (outlives this object) holds the initial garment; its current state is the
  /// first warm start. `objective` is the weighted sum of design terms (for THIS
  /// garment topology). Throws InputError/SolverError when the biharmonic coordinates
  /// cannot be built.
  /// `make_objective` (optional) rebuilds the objective after remeshing; without it
  /// remesh() is not available.
  DesignProblem(GarmentSimulation& sim, std::shared_ptr<const DesignTermSum> objective,
                DesignProblemOptions options = {}, ObjectiveFactory make_objective = {});

  GarmentSimulation& simulation() { return sim_; }
  const GarmentSimulation& simulation() const { return sim_; }
  const DesignTermSum& objective() const { return *ref_.objective; }
  const DesignProblemOptions& options() const { return options_; }
  const BiharmonicCoordinates& coordinates() const { return ref_.coordinates; }
  int num_parameters() const { return ref_.coordinates.num_parameters(); }
  /// p of the garment's rest positions at construction (or at the last remeshing).
  const VecX& initial_parameters() const { return ref_.initial_parameters; }

  /// Evaluates T (and dT/dp when `with_gradient`) at p; see the header comment.
  DesignEvaluation evaluate(const VecX& p, bool with_gradient = true);
  /// Adds dT/dp to `ev`, the result of the last evaluate() (successful, without
  /// gradient), at the simulation's current state. On an adjoint failure, or a gradient
  /// that is not finite, sets ev.ok = false and ev.failure and returns false.
  bool add_gradient(DesignEvaluation& ev);

  /// Makes the simulation's current state (the last successful evaluate()) and its p
  /// the accepted point: the warm start of every later evaluation.
  void accept();
  /// Puts the simulation back to the accepted parameters and equilibrium.
  void restore_accepted();
  /// Sets the accepted point directly (resuming from a checkpoint); the simulation is
  /// put there too. Throws InputError when sizes do not match this problem.
  /// `held_ordering`: the checkpoint's ordering for the factorization at the accepted
  /// point (accepted_ordering()); empty: search one.
  /// `held_point`: where the checkpoint's held factorization was made
  /// (accepted_held_point()); it is made again there. Absent: made at the accepted
  /// point by the first gradient. Throws InputError when its sizes do not match.
  void set_accepted(const VecX& p, const EmbeddedState& state,
                    const CholeskyOrdering& held_ordering = {},
                    const std::optional<HeldFactorizationPoint>& held_point = std::nullopt);

  const VecX& accepted_parameters() const { return accepted_p_; }
  const EmbeddedState& accepted_state() const { return accepted_state_; }
  /// The fill-reducing ordering the held factorization of the accepted point was
  /// analysed with (AdjointSolver::held_ordering; empty: its own search).
  const CholeskyOrdering& accepted_ordering() const { return accepted_ordering_; }
  /// Where the held factorization of the accepted point was made (nullopt: none held).
  const std::optional<HeldFactorizationPoint>& accepted_held_point() const {
    return accepted_held_;
  }

  /// Xbar(p) (n_p×2, m). Throws std::invalid_argument for a wrong length.
  Points2 rest_positions(const VecX& p) const;
  /// Smallest signed rest-area ratio (current / initial) over all triangles at p.
  double min_area_ratio(const VecX& p) const;
  /// The largest α (∞ when none binds) such that every pattern triangle's signed rest
  /// area at p + α d stays at least `fraction` (in (0, 1)) times its area at p: the
  /// bound a trial step keeps so that it never inverts or crushes a triangle (areas are
  /// quadratic in α, so the bound is exact).
  double max_step_keeping_areas(const VecX& p, const VecX& d, double fraction) const;
  /// Mean length (m) of the initial boundary edges (a natural step scale for p).
  double mean_boundary_edge() const { return ref_.mean_boundary_edge; }

  /// True when an objective factory was given (remesh() can rebuild the objective).
  bool can_remesh() const { return static_cast<bool>(make_objective_); }
  /// Target edge length (m) of every piece's new meshes: options().remesh.edge_length,
  /// or the piece's mean rest edge length at construction.
  const std::vector<double>& target_edge_lengths() const { return target_edge_; }
  /// Pieces whose rest mesh at the accepted parameters is degraded by the criteria of
  /// options().remesh: an inverted triangle; a smallest angle below min_angle_deg; a
  /// triangle smaller than min_area_fraction × the equilateral area of the target edge
  /// length. A piece whose fresh mesh already misses a criterion (e.g. a sharp corner
  /// of its outline) is held to 0.75 × its fresh value instead, so remeshing it does
  /// not repeat forever.
  std::vector<int> degraded_pieces() const;
  /// Remeshes `pieces` (see the header comment) at the accepted point; on success the
  /// accepted point is the remeshed pattern's equilibrium. Throws std::logic_error
  /// without an objective factory, SolverError (nothing changed) when the remeshed
  /// pattern or its transferred state is not finite.
  RemeshOutcome remesh(const std::vector<int>& pieces);

  /// After a successful remesh(): the remeshed pattern with the reference rest positions
  /// and each piece's mesh rest positions; nullopt while the garment is the one this
  /// problem was constructed with.
  std::optional<RemeshedDesign> remeshed_design() const;
  /// Puts this problem, constructed for the scene's garment, into the state after the
  /// remeshing described by `design` (from remeshed_design() of an earlier run): the
  /// simulation's garment becomes weld_pattern(design.pattern) at `state`, the
  /// biharmonic coordinates and fresh-mesh qualities are built from the mesh rest
  /// positions, the objective is rebuilt and the reference reset, exactly as after that
  /// remesh(); the accepted point is the reference at `state`. The target edge lengths
  /// stay those of the scene's garment. Throws InputError (source "checkpoint", naming
  /// the JSON path under /remeshed) when the design does not fit the scene's garment
  /// (pieces, seams, pinned boundaries), the state does not fit the design, or its
  /// meshes are invalid; std::logic_error without an objective factory.
  void restore_remeshed_design(const RemeshedDesign& design, const EmbeddedState& state);

  /// The accepted design in memory (garment, reference, parameters, equilibrium), to be
  /// put back by restore(): PatternOptimizer keeps its best design this way.
  struct Snapshot;
  Snapshot snapshot() const;
  /// Makes `snapshot` (taken from this problem) the accepted point again, on its garment
  /// (replaced when a remeshing changed it since); the simulation is put there.
  void restore(const Snapshot& snapshot);

 private:
  /// What the design parameters and evaluations refer to, for one garment topology: a
  /// remesh() builds a new one and swaps it in only when the remeshed problem solved.
  struct Reference {
    std::shared_ptr<const DesignTermSum> objective;
    BiharmonicCoordinates coordinates;
    Points2 initial_rest;             // n_p×2 (m): Xbar0
    VecX initial_parameters;          // p0 = the parameters of initial_rest
    VecX initial_areas;               // signed rest areas of the pattern triangles (m²)
    double mean_boundary_edge = 0.0;  // m, of initial_rest
    std::vector<PieceQuality> fresh;  // per piece: quality of its last fresh mesh
    std::vector<Points2> mesh_rest;   // per piece: rest positions its mesh was made with
  };

 public:
  struct Snapshot {
    Garment garment;
    Reference ref;
    bool remeshed = false;
    VecX parameters;
    EmbeddedState state;
  };

 private:
  /// The reference of the simulation's current garment at its current rest shape.
  Reference make_reference(std::shared_ptr<const DesignTermSum> objective,
                           BiharmonicCoordinates coordinates, std::vector<PieceQuality> fresh,
                           std::vector<Points2> mesh_rest) const;
  /// Makes the reference's initial point at the simulation's current state the
  /// accepted point.
  void accept_reference();
  /// evaluate() and add_gradient() against `ref`, warm-started from `start` with the
  /// held factorization `held` (may be null).
  DesignEvaluation evaluate_at(const Reference& ref, const VecX& p, const EmbeddedState& start,
                               const SparseCholesky* held, bool with_gradient);
  bool add_gradient_at(const Reference& ref, DesignEvaluation& ev);
  Points2 rest_positions_at(const Reference& ref, const VecX& p) const;
  double min_area_ratio_at(const Reference& ref, const VecX& p) const;
  /// Sets ev's equilibrium_move and moved_vertex* from the simulation's equilibrium.
  void record_equilibrium_move(const Points3& accepted_positions, DesignEvaluation& ev) const;

  GarmentSimulation& sim_;
  DesignProblemOptions options_;
  AdjointSolver adjoint_;
  ObjectiveFactory make_objective_;
  std::vector<double> target_edge_;  // per piece (m)
  Reference ref_;
  bool remeshed_ = false;  // a remesh() succeeded (or one was restored)
  VecX accepted_p_;
  EmbeddedState accepted_state_;
  CholeskyOrdering accepted_ordering_;
  VecX current_p_;  // parameters the simulation's rest positions are set to
  bool last_ok_ = false;
  /// Where the adjoint's held factorization was made (nullopt: none held).
  std::optional<HeldFactorizationPoint> current_held_point() const;

  EmbeddedState newton_state_;      // where the last forward solve last factorized
  bool newton_factorized_ = false;  // the last forward solve factorized (at newton_state_)
  VecX held_parameters_;  // p of the adjoint's held factorization (its state, shift: adjoint_)
  std::optional<HeldFactorizationPoint> accepted_held_;  // of the accepted point's
  long gradient_generation_ = -1;  // adjoint factorization made at the last evaluation
  long accepted_generation_ = -1;  // adjoint factorization made at the accepted point
};

}  // namespace tightfit
