#include "tightfit/design/adjoint_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

VecX flat_positions(const GarmentSimulation& sim) {
  const Points3& x = sim.garment_positions();
  return Eigen::Map<const VecX>(x.data(), x.size());
}

/// D = ∂²U/∂x² − P(∂²U/∂x²) over the rest-dependent (garment) energies (3·n_g × 3·n_g,
/// N/m): what Newton's element PSD projection took away, zero entries dropped (empty
/// when nothing was projected). The exact Hessian is H_N + Jᵀ D J, so it can be applied
/// to vectors without assembling it a second time.
SparseMatrix projection_difference(const GarmentSimulation& sim) {
  const VecX x = flat_positions(sim);
  SparseMatrix D(x.size(), x.size());
  if (!sim.problem().projects_hessians()) return D;
  std::vector<Triplet> exact, projected;
  for (const RestDependentEnergy* e : sim.rest_dependent_energies()) {
    e->add_hessian(x, exact, false);
    e->add_hessian(x, projected, true);
  }
  exact.reserve(exact.size() + projected.size());
  for (const Triplet& t : projected) exact.emplace_back(t.row(), t.col(), -t.value());
  D.setFromTriplets(exact.begin(), exact.end());
  D.prune(0.0);
  return D;
}

}  // namespace

SimulationDesignState::SimulationDesignState(const GarmentSimulation& sim)
    : x(flat_positions(sim)),
      rest(sim.garment().rest_positions()),
      garment(sim.problem().state().garment),
      body(sim.problem().state().body) {}

const char* adjoint_method_name(AdjointMethod method) {
  switch (method) {
    case AdjointMethod::kNone:
      return "none";
    case AdjointMethod::kDirect:
      return "direct";
    case AdjointMethod::kPreconditioned:
      return "preconditioned";
    case AdjointMethod::kFallback:
      return "fallback";
  }
  return "unknown";
}

SparseMatrix mixed_rest_derivative(const GarmentSimulation& sim) {
  const VecX x = flat_positions(sim);
  std::vector<Triplet> t;
  for (const RestDependentEnergy* e : sim.rest_dependent_energies()) e->add_mixed_rest(x, t);
  SparseMatrix M(x.size(), 2 * sim.garment().num_pattern_vertices());
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

AdjointResult AdjointSolver::rest_gradient(GarmentSimulation& sim, const DesignTerm& term) {
  const SimulationDesignState ds(sim);
  const DesignState state = ds.view();
  AdjointResult r;
  r.value = term.value(state);
  if (!std::isfinite(r.value))
    throw SolverError("adjoint: the design objective '" + term.name() + "' is not finite");
  r.explicit_x = VecX::Zero(ds.x.size());
  r.rest_gradient = VecX::Zero(2 * ds.rest.rows());
  term.add_gradient(state, r.explicit_x, r.rest_gradient);
  if (!r.explicit_x.allFinite() || !r.rest_gradient.allFinite())
    throw SolverError("adjoint: the gradient of '" + term.name() + "' is not finite");
  if (!term.depends_on_positions()) return r;

  EmbeddedEquilibrium& problem = sim.problem();
  const SparseMatrix J = problem.position_jacobian();
  VecX rhs = J.transpose() * r.explicit_x;  // ∂T/∂q
  if (term.depends_on_embedding()) {
    VecX d_s = VecX::Zero(2 * static_cast<Eigen::Index>(ds.garment.size()));
    VecX d_y = VecX::Zero(ds.body.size());
    term.add_embedding_gradient(state, d_s, d_y);
    if (!d_s.allFinite() || !d_y.allFinite())
      throw SolverError("adjoint: the gradient of '" + term.name() + "' is not finite");
    for (int i = 0; i < problem.num_garment_vertices(); ++i)
      if (const int dof = problem.garment_dof(i); dof >= 0)
        rhs.segment<2>(dof) += d_s.segment<2>(2 * i);
    for (Eigen::Index k = 0; k < ds.body.rows(); ++k)
      if (const int dof = problem.body_dof(static_cast<int>(k)); dof >= 0)
        rhs.segment<3>(dof) += d_y.segment<3>(3 * k);
  }
  if (rhs.squaredNorm() == 0.0) return r;  // x depends on no free DOF
  const AdjointSolve a = solve(sim, rhs);
  r.hessian_shift = a.hessian_shift;
  r.adjoint_residual = a.residual;
  r.method = a.method;
  r.krylov_iterations = a.krylov_iterations;
  r.factorizations = a.factorizations;
  r.solved = true;
  const VecX j_lambda = J * a.lambda;  // 3·n_g
  r.rest_gradient -= mixed_rest_derivative(sim).transpose() * j_lambda;
  if (!r.rest_gradient.allFinite())
    throw SolverError("adjoint: the design gradient is not finite (singular equilibrium?)");
  return r;
}

std::optional<double> AdjointSolver::factorize_held(const GarmentSimulation& sim,
                                                    const SparseMatrix& H_newton,
                                                    int& factorizations) {
  const ShiftSequence shifts = options_.shift_sequence();
  ++generation_;
  held_ordering_ = next_ordering_;
  const auto shift =
      factorize_shifted(newton_factor_, H_newton, shifts, factorizations, nullptr,
                        held_ordering_.permutation.empty() ? nullptr : &held_ordering_);
  held_valid_ = shift.has_value();
  held_shift_ = shift.value_or(0.0);
  held_state_ = sim.problem().state();
  held_rest_ = sim.rest_positions();
  if (held_valid_) next_ordering_ = newton_factor_.ordering();
  return shift;
}

bool AdjointSolver::factorize_held(GarmentSimulation& sim) {
  int factorizations = 0;
  return factorize_held(sim, sim.problem().hessian(HessianKind::kNewton), factorizations)
      .has_value();
}

bool AdjointSolver::factorize_held(GarmentSimulation& sim, double shift) {
  ++generation_;
  held_ordering_ = next_ordering_;
  held_valid_ =
      factorize_with_shift(newton_factor_, sim.problem().hessian(HessianKind::kNewton), shift,
                           held_ordering_.permutation.empty() ? nullptr : &held_ordering_);
  held_shift_ = held_valid_ ? shift : 0.0;
  held_state_ = sim.problem().state();
  held_rest_ = sim.rest_positions();
  if (held_valid_) next_ordering_ = newton_factor_.ordering();
  return held_valid_;
}

bool AdjointSolver::adopt(GarmentSimulation& sim, const EmbeddedState& state) {
  NewtonSolver& newton = sim.newton();
  if (newton.factorization().size() != sim.problem().num_dofs()) return false;
  newton.swap_factorization(newton_factor_);
  ++generation_;
  held_valid_ = true;
  held_shift_ = newton.factorization_shift();
  held_state_ = state;
  held_rest_ = sim.rest_positions();
  held_ordering_ = newton_factor_.ordering();
  next_ordering_ = held_ordering_;
  return true;
}

bool AdjointSolver::held_made_here(const GarmentSimulation& sim) const {
  if (!held_valid_) return false;
  const EmbeddedState& now = sim.problem().state();
  if (now.garment.size() != held_state_.garment.size() ||
      now.body.rows() != held_state_.body.rows() ||
      sim.rest_positions().rows() != held_rest_.rows())
    return false;
  for (size_t i = 0; i < now.garment.size(); ++i) {
    const SurfacePoint &a = now.garment[i], &b = held_state_.garment[i];
    if (a.face != b.face || a.u != b.u || a.v != b.v) return false;
  }
  return now.body == held_state_.body && sim.rest_positions() == held_rest_;
}

AdjointSolve AdjointSolver::solve(GarmentSimulation& sim, const VecX& rhs, bool force_fallback) {
  EmbeddedEquilibrium& problem = sim.problem();
  if (rhs.size() != problem.num_dofs())
    throw SolverError("adjoint: right-hand side has the wrong size");
  const ShiftSequence shifts = options_.shift_sequence();
  AdjointSolve out;
  // The exact H applied from its factors; H_N and what its projection took away (D, the
  // projected elements only: H = H_N + Jᵀ D J) only where a factorization is made here.
  const LinearOperator apply_exact = problem.hessian_operator(HessianKind::kExact);
  std::optional<SparseMatrix> H_newton;
  std::optional<bool> projected;
  auto newton_matrix = [&]() -> const SparseMatrix& {
    if (!H_newton) H_newton = problem.hessian(HessianKind::kNewton);
    return *H_newton;
  };
  auto anything_projected = [&] {
    if (!projected) projected = projection_difference(sim).nonZeros() > 0;
    return *projected;
  };
  auto residual_of = [&](const VecX& lambda) {
    return (apply_exact(lambda) - rhs).norm() / rhs.norm();
  };
  // A factorization held from before a remeshing is of another size: not usable.
  if (held_valid_ && newton_factor_.size() != rhs.size()) held_valid_ = false;
  bool here = held_made_here(sim);
  // λ from the held factorization: directly when it is H_N here and H_N is H, else by
  // GMRES preconditioned with it. False when GMRES does not converge.
  auto solve_with_held = [&](int max_iterations) {
    if (here && held_shift_ == 0.0 && !anything_projected()) {
      out.lambda = newton_factor_.solve(rhs);
      out.method = AdjointMethod::kDirect;
      out.residual = residual_of(out.lambda);
      return true;
    }
    GmresOptions gmres;
    gmres.relative_tolerance = options_.iterative_tolerance;
    gmres.max_iterations = max_iterations;
    VecX lambda = newton_factor_.solve(rhs);
    const GmresReport report = preconditioned_gmres(
        apply_exact, [&](const VecX& v) { return newton_factor_.solve_preconditioner(v); }, rhs,
        lambda, gmres);
    out.krylov_iterations += report.iterations;
    if (!report.converged || !lambda.allFinite()) return false;
    out.lambda = std::move(lambda);
    // No Krylov step needed: the held factorization solves H to the tolerance (here, H
    // and H_N differ by round-off only).
    out.method = report.iterations == 0 ? AdjointMethod::kDirect : AdjointMethod::kPreconditioned;
    out.residual = report.relative_residual;
    return true;
  };

  if (!force_fallback && held_valid_ && !here && solve_with_held(options_.max_reuse_iterations))
    return out;
  if (!force_fallback && !here) {
    const auto newton_shift = factorize_held(sim, newton_matrix(), out.factorizations);
    here = true;
    if (newton_shift && solve_with_held(options_.max_iterative_iterations)) return out;
  } else if (!force_fallback && held_valid_ && solve_with_held(options_.max_iterative_iterations)) {
    return out;
  }
  const SparseMatrix H =
      problem.projects_hessians() ? problem.hessian(HessianKind::kExact) : newton_matrix();
  double last = 0.0;
  const auto shift = factorize_shifted(exact_factor_, H, shifts, out.factorizations, &last);
  if (!shift)
    throw SolverError(
        "adjoint: the equilibrium Hessian could not be factorized even with diagonal shift " +
        std::to_string(last) + " N/m");
  out.hessian_shift = *shift;
  out.lambda = exact_factor_.solve(rhs);
  out.method = AdjointMethod::kFallback;
  out.residual = residual_of(out.lambda);
  return out;
}

}  // namespace tightfit
