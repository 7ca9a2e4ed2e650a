#pragma once
/// Newton's method with a backtracking line search on the total energy and
/// exponentially growing diagonal regularization when the Hessian is not positive
/// definite (paper Sec. 3.3). Failure is reported as a SolverError naming the residual.
#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/solve/newton_problem.hpp"

namespace tightfit {

struct NewtonIteration;

/// Tolerances in SI units. Converged when force_norm(g) ≤ max(absolute_force_tolerance,
/// relative_force_tolerance · force_scale()).
struct NewtonOptions {
  double relative_force_tolerance = 1e-9;   ///< relative to the problem's force scale
  double absolute_force_tolerance = 1e-12;  ///< N
  int max_iterations = 100;                 ///< iterations that factorize a Hessian
                                            ///< (chord steps are not counted)
  int max_line_search_halvings = 40;
  double armijo = 1e-4;                  ///< sufficient-decrease constant
  double initial_regularization = 1e-8;  ///< first diagonal shift, relative to mean |diag(H)|
  double regularization_growth = 10.0;   ///< factor between regularization attempts
  int max_regularizations = 30;
  /// Where a Hessian is not positive definite and no shift of this solve is known, the
  /// first shift is estimated by this many Lanczos steps (ShiftSequence::estimate_steps:
  /// a product with H each, against the failed factorizations of a search climbing from
  /// `initial_regularization` one decade at a time). 0: no estimate.
  int shift_estimate_steps = 80;
  bool throw_on_failure = true;  ///< throw SolverError if not converged
  /// Chord steps (solve()'s ChordSteps): steps with a factorization that is already
  /// there instead of a new one. At most this many in a
  /// row, and only while each reduces the force norm to at most `chord_contraction`
  /// times the previous one; then a new factorization. 0: plain Newton.
  int max_chord_steps = 4;
  double chord_contraction = 0.25;
  /// Chord steps as Newton–Krylov steps where the problem offers hessian_operator():
  /// the Newton system at the current state solved by conjugate gradients preconditioned
  /// with the held factorization, its factor rounded to single precision
  /// (SparseCholesky::solve_preconditioner; truncated_cg.hpp) to `krylov_tolerance` (relative
  /// residual) in at most `krylov_iterations` products; when CG does not get there the
  /// next step factorizes. false: plain chord steps, dq = −F⁻¹ g.
  bool krylov_chords = true;
  double krylov_tolerance = 1e-3;
  int krylov_iterations = 20;
  /// Eisenstat–Walker forcing ("choice 2", SIAM J. Sci. Comput. 17, 1996): the CG
  /// tolerance of a Newton–Krylov step is η_k = γ (‖g_k‖ / ‖g_{k−1}‖)², at least γ η_{k−1}²
  /// when that exceeds 0.1, kept within [krylov_tolerance, krylov_max_tolerance] — loose
  /// while the force falls slowly (far from the equilibrium a precise solve of a model
  /// that does not hold is wasted), tight as Newton converges. The first step of a solve
  /// uses krylov_tolerance. γ = krylov_forcing (0: always krylov_tolerance).
  double krylov_forcing = 0.9;
  double krylov_max_tolerance = 0.5;
  /// Acceptance by force where the energy cannot tell. Near an equilibrium the energy
  /// change of a step is a difference of parts that cancel (a garment pressing on the
  /// body: their changes agree to ~1e-3), and inside the Gregory regions of the limit
  /// surface its derivatives are not exactly those of its positions (limit_surface.hpp),
  /// so a full Newton step that cuts the force tenfold can show a rise of the total
  /// energy at ~1e-12 of it, and the Armijo test would stall the solve on tiny steps. A
  /// full step whose model is positive definite (an unshifted factorization, or a
  /// Newton–Krylov step whose CG converged without negative curvature) is therefore also
  /// accepted when the energy rises by at most `energy_precision` × |energy| and the force
  /// norm falls to at most `force_merit_contraction` × its value (0: never).
  double energy_precision = 1e-10;
  double force_merit_contraction = 0.5;
  /// Called after every accepted step with its record (forces before the step) and the
  /// seconds since the solve started: progress reports of long solves. Not part of the
  /// numerics; empty by default.
  std::function<void(const NewtonIteration&, double seconds)> on_step;

  /// The force tolerance (N) the convergence test applies to a problem of this force scale.
  double force_tolerance(double force_scale) const {
    return std::max(absolute_force_tolerance, relative_force_tolerance * force_scale);
  }
  /// The shifts tried where a Hessian is not positive definite (factorize_shifted).
  ShiftSequence shift_sequence() const {
    ShiftSequence shifts{initial_regularization, regularization_growth, max_regularizations};
    shifts.estimate_steps = shift_estimate_steps;
    return shifts;
  }
};

/// One Newton iteration, for reports and convergence tests.
struct NewtonIteration {
  double energy = 0.0;             ///< J, before the step
  double force_norm = 0.0;         ///< N, before the step
  double step_size = 0.0;          ///< accepted line-search alpha
  double regularization = 0.0;     ///< diagonal shift δ used (N/m at a DOF of mean
                                   ///< stiffness, ShiftSequence; 0 if none)
  bool chord = false;              ///< step from the held factorization (no new Hessian)
  int krylov_iterations = 0;       ///< of a chord step: conjugate-gradient products
  double krylov_tolerance = 0.0;   ///< of a Newton–Krylov step: the relative residual
                                   ///< CG was asked for (NewtonOptions::krylov_forcing)
  bool body_held = false;          ///< a step of the first stage on the garment alone, the
                                   ///< body held still (NewtonReport::garment_first_iterations)
  bool accepted_by_force = false;  ///< accepted by its force decrease, not by the energy
                                   ///< (NewtonOptions::energy_precision)
  double seconds_assembly = 0.0;   ///< gradient + Hessian
  double seconds_factorization = 0.0;
  double seconds_solve = 0.0;
  double seconds_line_search = 0.0;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;            ///< steps taken (chord steps included)
  int chord_steps = 0;           ///< of them: with the held factorization
  int factorizations = 0;        ///< Hessians factorized (shifted retries included)
  int krylov_iterations = 0;     ///< conjugate-gradient products of the chord steps
  int force_accepted_steps = 0;  ///< steps accepted by their force decrease
  /// Of `iterations`: steps of a stage on the garment alone, the body held still
  /// (GarmentSimulation::relax_garment_on_still_body; their records are marked body_held).
  int garment_first_iterations = 0;
  double final_energy = 0.0;
  double final_force_norm = 0.0;  ///< N
  double tolerance = 0.0;         ///< N, the force tolerance that was applied
  std::vector<NewtonIteration> history;
  std::int64_t hessian_nonzeros = 0;
  std::int64_t factor_nonzeros = 0;
  double seconds_total = 0.0;
  std::string message;  ///< why it stopped
  /// Stopped by ChordSteps::stop_after_poor_predictor (not converged, no exception).
  bool stopped_after_predictor = false;
};

/// Factorizations a solve may use for chord steps dq = −F⁻¹ g instead of factorizing new
/// Hessians (NewtonSolver::solve).
struct ChordSteps {
  /// A factorization of a Hessian of the same system near the starting state (null: none).
  const SparseCholesky* held = nullptr;
  /// Also reuse each Newton step's own factorization for the steps after it.
  bool reuse_own = false;
  /// Called after each Hessian factorization of the solve, with the problem still at the
  /// state it was assembled at (e.g. to record where factorization() was made).
  std::function<void()> on_factorized = nullptr;
  /// Stop after the first step when it was a step with `held` (the predictor of a warm
  /// start) that the line search shortened (or took back), or that left more than
  /// NewtonOptions::chord_contraction of the force: the start is outside the region where
  /// the held factorization's linear model holds, and Newton would factorize at once. For callers
  /// with a cheaper way to get closer first (GarmentSimulation relaxes the garment alone);
  /// NewtonReport::stopped_after_predictor.
  bool stop_after_poor_predictor = false;
};

class NewtonSolver {
 public:
  explicit NewtonSolver(NewtonOptions options = {}) : options_(options) {}

  /// Runs Newton from the problem's current (committed) state; on return the problem
  /// holds the last accepted state. Throws SolverError when not converged and
  /// options.throw_on_failure.
  ///
  /// `chords.held` (optional): the factorization of a Hessian of the same system near
  /// the starting state (e.g. at the previous equilibrium of a design step, whose rest
  /// shape differs a little). The first steps are then chord steps dq = −held⁻¹ g, which
  /// cost a gradient and a solve but no assembly or factorization of a Hessian; the
  /// first chord step from an equilibrium of the old rest shape is the first-order
  /// predictor of the new equilibrium, −H⁻¹ (∂g/∂Xbar) ΔXbar. With `chords.reuse_own`,
  /// each Newton step's own factorization is reused the same way (a Shamanskii-type
  /// method: superlinear instead of quadratic, far fewer factorizations). Chord steps
  /// stop after
  /// options.max_chord_steps in a row or when one contracts the force norm by less than
  /// options.chord_contraction, and a new Hessian is factorized; the convergence test
  /// is the same for every step. A `held` of another size is ignored. Newton's own
  /// factorizations reuse `held`'s fill-reducing ordering (their patterns differ from
  /// held's only where garment vertices slid onto other faces), so the result of a
  /// solve is a function of the problem and `held`. When a Hessian
  /// needs a diagonal shift, the next one in the same solve starts its shifts one step
  /// below the shift that worked.
  NewtonReport solve(NewtonProblem& problem, ChordSteps chords = {});

  /// The factorization of the last Hessian that was factorized (at the state before the
  /// last full Newton step).
  const SparseCholesky& factorization() const { return cholesky_; }
  /// The diagonal shift δ of factorization() (ShiftSequence's scaling; 0: unshifted):
  /// factorize_with_shift(H, δ) makes it again from its Hessian H.
  double factorization_shift() const { return factorization_shift_; }
  /// Hands factorization() over to `into` by exchanging the two (nothing is copied); the
  /// solver then holds what `into` held and factorizes anew before using its own.
  void swap_factorization(SparseCholesky& into) noexcept { cholesky_.swap(into); }

  const NewtonOptions& options() const { return options_; }

 private:
  /// Factorizes H + δS (ShiftSequence: S scales the shift by each DOF's stiffness) with the
  /// smallest δ of the growing sequence that succeeds.
  /// Counts the attempts in `factorizations`. A new symbolic analysis uses `ordering`
  /// when given (SparseCholesky::factorize).
  double factorize_regularized(const SparseMatrix& H, int& factorizations,
                               const CholeskyOrdering* ordering);

  /// The full step at the problem's current (trial) state may be accepted by its force
  /// decrease (NewtonOptions::energy_precision): the energy rose by at most the energy
  /// precision and the force norm fell enough from `force_norm` (N).
  bool accept_by_force(NewtonProblem& problem, double energy, double new_energy,
                       double force_norm) const;

  /// The CG tolerance η of a Newton–Krylov step at force norm `force` after a step from
  /// `previous_force` (0: the first of the solve) that had `previous_tolerance`
  /// (NewtonOptions::krylov_forcing).
  double krylov_tolerance(double force, double previous_force, double previous_tolerance) const;

  /// The state of one solve() between its steps (newton_solver.cpp).
  struct SolveRun;
  /// The stop tests before the step of iteration `it` at gradient `g`: converged, a poor
  /// predictor (ChordSteps::stop_after_poor_predictor), the iteration limit. Fills the
  /// record's energy and force norm and the report's final values; sets the report's
  /// message when it stops.
  bool stops_before_step(SolveRun& run, int it, const VecX& g, NewtonIteration& record) const;
  /// Chooses the factorization of the step: the current one for a chord step while it
  /// contracts the force fast enough, else a new one of the Hessian at this state.
  /// `t0`: when the iteration began (its assembly time counts from there).
  void prepare_factorization(SolveRun& run, NewtonIteration& record,
                             std::chrono::steady_clock::time_point t0);
  /// The step dq: the factorization's solve of −g, or for a Newton–Krylov chord step
  /// conjugate gradients preconditioned with it.
  VecX step_direction(SolveRun& run, NewtonIteration& record, const VecX& g);
  /// Backtracking from the full step dq (Armijo with a round-off allowance, or the
  /// force test of accept_by_force); true with the record's step size and the run's
  /// energy set when a step is accepted (the problem then holds it, uncommitted).
  bool line_search(SolveRun& run, NewtonIteration& record, const VecX& g, const VecX& dq);
  /// The SolverError of a solve that did not converge, naming where the largest force
  /// acts at the problem's (last accepted) state.
  [[noreturn]] void throw_not_converged(NewtonProblem& problem, const NewtonReport& report) const;

  NewtonOptions options_;
  SparseCholesky cholesky_;
  double shift_hint_ = 0.0;           // last successful shift in this solve() (0: none needed)
  double factorization_shift_ = 0.0;  // δ of cholesky_
};

}  // namespace tightfit
