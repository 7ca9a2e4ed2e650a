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

}  // namespace

SimulationDesignState::SimulationDesignState(const GarmentSimulation& sim)
    : x(flat_positions(sim)), rest(sim.garment().rest_positions()) {}

const char* adjoint_method_name(AdjointMethod method) {
  switch (method) {
    case AdjointMethod::kNone: return "none";
    case AdjointMethod::kDirect: return "direct";
    case AdjointMethod::kPreconditioned: return "preconditioned";
    case AdjointMethod::kFallback: return "fallback";
  }
  return "unknown";
}

SparseMatrix exact_equilibrium_hessian(GarmentSimulation& sim) {
  return sim.problem().hessian(HessianKind::kExact);
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
  if (!term.depends_on_positions() || r.explicit_x.squaredNorm() == 0.0) return r;

  EmbeddedEquilibrium& problem = sim.problem();
  const SparseMatrix J = problem.position_jacobian();
  const VecX rhs = J.transpose() * r.explicit_x;  // ∂T/∂q
  if (rhs.squaredNorm() == 0.0) return r;         // x depends on no free DOF
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

namespace {

bool same_matrix(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const auto nnz = static_cast<size_t>(a.nonZeros());
  const auto cols = static_cast<size_t>(a.cols()) + 1;
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + cols, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + nnz, b.valuePtr());
}

}  // namespace

std::optional<double> AdjointSolver::factorize_held(const SparseMatrix& H_newton,
                                                    int& factorizations) {
  const ShiftSequence shifts{options_.initial_regularization, options_.regularization_growth,
                             options_.max_regularizations};
  ++generation_;
  const auto shift = factorize_shifted(newton_factor_, H_newton, shifts, factorizations);
  held_valid_ = shift.has_value();
  return shift;
}

bool AdjointSolver::factorize_held(GarmentSimulation& sim) {
  int factorizations = 0;
  return factorize_held(sim.problem().hessian(HessianKind::kNewton), factorizations).has_value();
}

AdjointSolve AdjointSolver::solve(GarmentSimulation& sim, const VecX& rhs, bool force_fallback) {
  EmbeddedEquilibrium& problem = sim.problem();
  if (rhs.size() != problem.num_dofs())
    throw SolverError("adjoint: right-hand side has the wrong size");
  const ShiftSequence shifts{options_.initial_regularization, options_.regularization_growth,
                             options_.max_regularizations};
  AdjointSolve out;
  const SparseMatrix H_newton = problem.hessian(HessianKind::kNewton);
  const auto newton_shift = factorize_held(H_newton, out.factorizations);
  const SparseMatrix H =
      problem.projects_hessians() ? problem.hessian(HessianKind::kExact) : H_newton;
  auto residual_of = [&](const VecX& lambda) { return (H * lambda - rhs).norm() / rhs.norm(); };

  if (!force_fallback && held_valid_ && *newton_shift == 0.0 && same_matrix(H, H_newton)) {
    out.lambda = newton_factor_.solve(rhs);
    out.method = AdjointMethod::kDirect;
    out.residual = residual_of(out.lambda);
    return out;
  }
  if (!force_fallback && held_valid_) {
    GmresOptions gmres;
    gmres.relative_tolerance = options_.iterative_tolerance;
    gmres.max_iterations = options_.max_iterative_iterations;
    VecX lambda = newton_factor_.solve(rhs);  // the solution where nothing was projected
    const GmresReport report = preconditioned_gmres(
        [&](const VecX& v) { return VecX(H * v); },
        [&](const VecX& v) { return newton_factor_.solve(v); }, rhs, lambda, gmres);
    out.krylov_iterations = report.iterations;
    if (report.converged && lambda.allFinite()) {
      out.lambda = std::move(lambda);
      // No Krylov step needed: H and H_N differ by round-off only (projections of
      // eigenvalues that are zero up to round-off).
      out.method = report.iterations == 0 ? AdjointMethod::kDirect : AdjointMethod::kPreconditioned;
      out.residual = report.relative_residual;
      return out;
    }
  }
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
