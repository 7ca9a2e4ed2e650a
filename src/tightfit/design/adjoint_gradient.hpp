#pragma once
/// Adjoint sensitivity analysis (paper Sec. 4, Eq. 21-23 with the transposes of
/// DESIGN.md §4): the gradient of a design term T(x(q), Xbar) with respect to the
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
/// an element is indefinite. The adjoint uses the unprojected Hessian
///   H = H_newton + Jᵀ (H_xx − P(H_xx)) J
/// (H_xx: Hessian of the garment energies in x, P: per-element PSD projection), which
/// equals ∂g/∂q including the second-derivative terms of Eq. 18.
///
/// Indefinite H. At a stable equilibrium H is positive semi-definite; it is singular
/// where the equilibrium is not locally unique (e.g. slack or wrinkled cloth with no
/// stiffness along a direction the objective cares about). If the Cholesky
/// factorization of H fails, H + δI is factorized with the smallest δ of a growing
/// sequence (as in Newton) and the result reports δ > 0: that gradient is then NOT the
/// exact derivative (it is the gradient of a problem whose equilibrium is stiffened by
/// δ), only a descent-ish direction. Callers should surface `hessian_shift`.
///
/// Terms that do not depend on x (the regularizers) need no linear solve.
#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/design/design_term.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

struct AdjointOptions {
  /// First diagonal shift tried when the exact Hessian is not positive definite,
  /// relative to the mean |diag(H)|.
  double initial_regularization = 1e-10;
  double regularization_growth = 10.0;  ///< factor between shifts
  int max_regularizations = 30;
};

/// The gradient of a design term at the simulation's current (equilibrium) state.
struct AdjointResult {
  double value = 0.0;             ///< T at the state (the term's units)
  VecX rest_gradient;             ///< dT/dXbar (length 2·n_p, DOF 2·v + k), units of T per m
  VecX explicit_x;                ///< ∂T/∂x (3·n_g), for diagnostics
  bool solved = false;            ///< an adjoint system was solved (T depends on x)
  double hessian_shift = 0.0;     ///< absolute diagonal shift δ (N/m); 0: exact gradient
  double adjoint_residual = 0.0;  ///< ‖H λ − ∂T/∂q‖ / ‖∂T/∂q‖ with the exact H
};

/// The exact Hessian ∂g/∂q (n_dofs × n_dofs, N/m) of the simulation's total energy at
/// its current state (see the header comment on the projection).
SparseMatrix exact_equilibrium_hessian(GarmentSimulation& sim);

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

  const AdjointOptions& options() const { return options_; }

 private:
  AdjointOptions options_;
  SparseCholesky cholesky_;
};

/// The design state (x, Xbar) of the simulation's current garment: x flat (3·n_g, m)
/// and Xbar stacked (n_p×2, m). Kept together so that DesignState's references stay valid.
struct SimulationDesignState {
  VecX x;
  Points2 rest;
  explicit SimulationDesignState(const GarmentSimulation& sim);
  DesignState view() const { return {x, rest}; }
};

}  // namespace tightfit
