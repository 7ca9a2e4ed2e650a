#pragma once
/// Adjoint sensitivity analysis (paper Sec. 4, Eq. 21-23 with the transposes of
/// docs/design.md §4): the gradient of a design term T(x(q), Xbar) with respect to the
/// pattern rest positions Xbar, with the equilibrium q(Xbar) of the garment simulation
/// followed implicitly.
///
/// At an equilibrium g(q, Xbar) = ∂U/∂q = 0 (U = cloth + seams + body),
///   dT/dXbar = ∂T/∂Xbar − (∂g/∂Xbar)ᵀ λ,      H λ = ∂T/∂q = Jᵀ ∂T/∂x,
///   ∂g/∂Xbar = Jᵀ ∂²U/∂x∂Xbar,
/// so (∂g/∂Xbar)ᵀ λ = (∂²U/∂x∂Xbar)ᵀ (J λ). Here J = dx/dq (3·n_g × n_dofs, the
/// position Jacobian of Eq. 18), H = ∂g/∂q the EXACT Hessian of U at the equilibrium
/// and ∂²U/∂x∂Xbar the mixed derivatives of the rest-dependent energies (cloth and
/// seam springs; the body energy does not depend on Xbar and J does not depend on
/// Xbar). The chain to the design parameters p is dT/dp = Wᵀ dT/dXbar
/// (BiharmonicCoordinates::pull_back).
///
/// Exact Hessian. The simulation's Newton matrix projects each cloth/seam element
/// Hessian onto the PSD cone (a descent safeguard) and is therefore not ∂g/∂q wherever
/// an element is indefinite. The adjoint system uses the exact Hessian, including the
/// second-derivative terms of Eq. 18, applied from its factors
/// (EmbeddedEquilibrium::hessian_operator(HessianKind::kExact); assembled only for the
/// fallback).
///
/// No factorization of its own in most gradients. The adjoint system is solved with a
/// HELD factorization of a Newton matrix H_N (the same sparsity pattern as every Newton
/// iteration, so the symbolic analysis is done once per garment topology):
///  * the forward solve's last factorization, handed over (adopt()) when the forward solve
///    factorized without a diagonal shift (DesignProblem): H_N at a state one or two
///    Newton steps before the equilibrium;
///  * otherwise the factorization held before (made at an earlier point).
/// H λ = ∂T/∂q is solved by GMRES preconditioned with it to `iterative_tolerance` in at
/// most `max_reuse_iterations` (a preconditioner from a nearby state takes a handful),
/// starting from the held factorization's own solution; the preconditioner applies its
/// factor rounded to single precision (SparseCholesky::solve_preconditioner), GMRES's
/// residuals are of the exact H.
/// Only when that fails is H_N factorized at the equilibrium itself (it becomes the held
/// factorization); then
///  * when no element was projected, H_N is the exact H and λ is one direct solve (so
///    too when projections changed H only by round-off: GMRES stops before its first
///    step);
///  * otherwise GMRES preconditioned with it (H and H_N differ only on the projected
///    elements) to `iterative_tolerance`;
///  * only when GMRES does not converge is H itself factorized (the fallback, reported as
///    AdjointMethod::kFallback).
/// The held factorization is what the forward solves of the next design trials start
/// their chord steps with (NewtonSolver::solve's `held`): the first one is the
/// first-order equilibrium predictor. DesignProblem records where it was made, so that a
/// resumed run makes it again (factorize_held(sim, shift)) and continues bit for bit.
///
/// Indefinite H. At a stable equilibrium H is positive semi-definite; it is singular
/// where the equilibrium is not locally unique (e.g. slack or wrinkled cloth with no
/// stiffness along a direction the objective cares about). GMRES solves an indefinite
/// but regular system exactly. In the fallback, if the Cholesky factorization of H fails,
/// H + δS (S: ShiftSequence's diagonal scaling) is factorized with the smallest δ of a
/// growing sequence (as in Newton) and the result reports δ > 0: that gradient is then NOT the
/// exact derivative (it is the gradient of a problem whose equilibrium is stiffened by δ), only a
/// descent-ish direction. Callers should surface `hessian_shift`.
///
/// Terms that do not depend on x (the regularizers) need no linear solve.
#include <optional>

#include "tightfit/common/preconditioned_gmres.hpp"
#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

struct AdjointOptions {
  /// First diagonal shift tried when the exact Hessian is not positive definite,
  /// relative to the mean |diag(H)|.
  double initial_regularization = 1e-10;
  double regularization_growth = 10.0;  ///< factor between shifts
  int max_regularizations = 30;
  /// Lanczos steps that estimate the first shift (ShiftSequence::estimate_steps; 0: climb
  /// from initial_regularization one factorization per decade).
  int shift_estimate_steps = 80;
  /// Relative residual ‖H λ − ∂T/∂q‖ / ‖∂T/∂q‖ the preconditioned GMRES solve reaches.
  double iterative_tolerance = 1e-12;
  /// GMRES iterations before the fallback factorizes the exact H.
  int max_iterative_iterations = 100;
  /// GMRES iterations a held factorization made at another state may take before H_N is
  /// factorized at the equilibrium instead (one iteration costs two triangular solves
  /// and a product with H: a few dozen cost about one assembly and factorization).
  int max_reuse_iterations = 30;

  /// The shifts tried where a matrix is not positive definite (factorize_shifted).
  ShiftSequence shift_sequence() const {
    ShiftSequence shifts{initial_regularization, regularization_growth, max_regularizations};
    shifts.estimate_steps = shift_estimate_steps;
    return shifts;
  }
};

/// How the adjoint system was solved.
enum class AdjointMethod {
  kNone,            ///< no system (the term does not depend on positions)
  kDirect,          ///< one solve with the factorization of H_N, which solves the exact
                    ///< system to the tolerance (nothing projected beyond round-off)
  kPreconditioned,  ///< GMRES on H, preconditioned by the factorization of H_N
  kFallback,        ///< GMRES did not converge: H factorized (maybe shifted)
};

/// "none", "direct", "preconditioned", "fallback".
const char* adjoint_method_name(AdjointMethod method);

/// The gradient of a design term at the simulation's current (equilibrium) state.
struct AdjointResult {
  double value = 0.0;             ///< T at the state (the term's units)
  VecX rest_gradient;             ///< dT/dXbar (length 2·n_p, DOF 2·v + k), units of T per m
  VecX explicit_x;                ///< ∂T/∂x (3·n_g), for diagnostics
  bool solved = false;            ///< an adjoint system was solved (T depends on x)
  double hessian_shift = 0.0;     ///< absolute diagonal shift δ (N/m); 0: exact gradient
  double adjoint_residual = 0.0;  ///< ‖H λ − ∂T/∂q‖ / ‖∂T/∂q‖ with the exact H
  AdjointMethod method = AdjointMethod::kNone;
  int krylov_iterations = 0;  ///< GMRES iterations (kPreconditioned, kFallback)
  int factorizations = 0;     ///< Cholesky factorizations done for this gradient
};

/// The solve of the adjoint system H λ = rhs at the simulation's current state.
struct AdjointSolve {
  VecX lambda;
  double hessian_shift = 0.0;  ///< N/m, 0 unless the fallback had to shift H
  double residual = 0.0;       ///< ‖H λ − rhs‖ / ‖rhs‖
  AdjointMethod method = AdjointMethod::kNone;
  int krylov_iterations = 0;
  int factorizations = 0;
};

/// ∂²U/∂x∂Xbar (3·n_g × 2·n_p, N/m) of the simulation's rest-dependent energies at the
/// current garment positions.
SparseMatrix mixed_rest_derivative(const GarmentSimulation& sim);

/// Computes adjoint gradients; keeps the Cholesky symbolic analysis between calls.
class AdjointSolver {
 public:
  explicit AdjointSolver(AdjointOptions options = {}) : options_(options) {}

  /// dT/dXbar at the simulation's current state, which must be an equilibrium (the
  /// formula assumes g = 0). Throws SolverError when H cannot be factorized even with
  /// the largest shift, or when T or its gradient is not finite.
  AdjointResult rest_gradient(GarmentSimulation& sim, const DesignTerm& term);

  /// Solves H λ = rhs (rhs of length n_dofs) at the simulation's current state by the
  /// method of the header comment. `force_fallback` skips to the direct factorization
  /// of H (the reference the iterative path is tested against). Throws SolverError
  /// when no method succeeds.
  AdjointSolve solve(GarmentSimulation& sim, const VecX& rhs, bool force_fallback = false);

  /// The held factorization: Newton's matrix H_N at held_state() (shifted by
  /// held_shift()), null while none is held. Its generation() grows with every new one
  /// (made or adopted), so a holder can tell whether it is still the one it took.
  const SparseCholesky* held_factorization() const {
    return held_valid_ ? &newton_factor_ : nullptr;
  }
  long generation() const { return generation_; }
  /// The fill-reducing ordering the held factorization was analysed with (empty: it
  /// searched its own). Each held factorization is analysed with the ordering the
  /// previous one found (SparseCholesky's fill rule decides when a new one is
  /// searched), so METIS runs once per garment topology, not once per iteration. A
  /// checkpoint stores it and set_next_ordering() gives it back on resume, so the
  /// resumed run factorizes exactly as the uninterrupted one did.
  const CholeskyOrdering& held_ordering() const { return held_ordering_; }
  /// The ordering the next held factorization is analysed with.
  void set_next_ordering(CholeskyOrdering ordering) { next_ordering_ = std::move(ordering); }
  /// Factorizes Newton's matrix at the simulation's current state as solve() does (it
  /// becomes the held factorization, made here; a new generation). Returns false when it
  /// is not positive definite even with the largest shift (nothing is held then).
  bool factorize_held(GarmentSimulation& sim);
  /// Makes a held factorization again: Newton's matrix at the simulation's current state
  /// and rest positions shifted by `shift` (factorize_with_shift), analysed with the
  /// next ordering (set_next_ordering). Returns false (nothing held) when that matrix is
  /// not positive definite.
  bool factorize_held(GarmentSimulation& sim, double shift);
  /// Takes over the forward solve's last factorization (NewtonSolver::swap_factorization)
  /// as the held one (a new generation): Newton's matrix at `state` (where that solve
  /// factorized it) and the simulation's current rest positions. Returns false, holding
  /// nothing new, when the solver's factorization is not of the simulation's size.
  bool adopt(GarmentSimulation& sim, const EmbeddedState& state);
  /// The diagonal shift δ of the held factorization (0: unshifted).
  double held_shift() const { return held_shift_; }
  /// The state the held factorization's Newton matrix was assembled at.
  const EmbeddedState& held_state() const { return held_state_; }
  /// True when the held factorization is Newton's matrix at the simulation's current
  /// state and rest positions.
  bool held_made_here(const GarmentSimulation& sim) const;

  const AdjointOptions& options() const { return options_; }

 private:
  /// factorize_held() with the matrix already assembled (at sim's state); returns the
  /// shift used.
  std::optional<double> factorize_held(const GarmentSimulation& sim, const SparseMatrix& H_newton,
                                       int& factorizations);

  AdjointOptions options_;
  SparseCholesky newton_factor_;
  SparseCholesky exact_factor_;
  bool held_valid_ = false;
  double held_shift_ = 0.0;   // its diagonal shift
  EmbeddedState held_state_;  // where it was made
  Points2 held_rest_;
  long generation_ = 0;
  CholeskyOrdering held_ordering_;  // what the held factorization was analysed with
  CholeskyOrdering next_ordering_;  // what the next one will be
};

/// The design state (x, Xbar) of the simulation's current garment: x flat (3·n_g, m)
/// and Xbar stacked (n_p×2, m). Kept together so that DesignState's references stay valid.
struct SimulationDesignState {
  VecX x;
  Points2 rest;
  std::vector<SurfacePoint> garment;  ///< the embedding (surface points)
  Points3 body;                       ///< body positions (n_b×3, m)
  DesignEmbedding embedding{garment, body};
  explicit SimulationDesignState(const GarmentSimulation& sim);
  SimulationDesignState(const SimulationDesignState&) = delete;
  SimulationDesignState& operator=(const SimulationDesignState&) = delete;
  DesignState view() const { return {x, rest, &embedding}; }
};

}  // namespace tightfit
