#pragma once
/// The interface Newton's method sees. The physics (a sum of energies over an
/// embedded garment and a body) lives behind it; the solver knows only energies,
/// gradients, Hessians and how to take a step.
#include <optional>
#include <string>

#include "tightfit/common/preconditioned_gmres.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

class NewtonProblem {
 public:
  virtual ~NewtonProblem() = default;

  /// Number of degrees of freedom n (length of gradients and steps).
  virtual Eigen::Index num_dofs() const = 0;

  /// Total energy at the current state (J). +infinity marks an inadmissible state
  /// (e.g. an inverted tetrahedron), which the line search rejects.
  virtual double energy() = 0;
  /// Gradient dU/dq at the current state (n).
  virtual VecX gradient() = 0;
  /// Hessian d²U/dq² at the current state (n×n, symmetric, both triangles stored).
  virtual SparseMatrix hessian() = 0;
  /// The product v ↦ hessian()·v at the current state, where the problem can apply it
  /// more cheaply than assembling hessian() (Newton–Krylov steps); nullopt: it cannot.
  virtual std::optional<LinearOperator> hessian_operator() { return std::nullopt; }

  /// Sets the state to (committed state) ⊕ alpha·dq. The problem decides what ⊕ is
  /// (a garment vertex walks across body faces). Returns false when the step cannot be
  /// taken (the line search then shortens it).
  virtual bool set_step(const VecX& dq, double alpha) = 0;
  /// Makes the current state the base of the next steps.
  virtual void commit() = 0;

  /// A norm of the gradient in force units (N), used for the convergence test.
  virtual double force_norm(const VecX& gradient) { return gradient.norm(); }
  /// A characteristic force (N) of the problem; the relative tolerance is relative to it.
  virtual double force_scale() { return 1.0; }
  /// Where the force of `gradient` is largest, in words a user can find it by (e.g.
  /// "0.42 N on garment vertex 17 (piece 'front') at (0.12, 0.85, 0.03) m"), for the
  /// message of a solve that did not converge; empty when the problem cannot say.
  virtual std::string locate_largest_force(const VecX& gradient) { return {}; }
};

}  // namespace tightfit
