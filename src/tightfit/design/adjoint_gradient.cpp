#include "tightfit/design/adjoint_gradient.hpp"

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

/// The garment energies of the simulation that depend on Xbar (cloth, seam springs):
/// exactly the garment energies of its equilibrium problem.
std::vector<const RestDependentEnergy*> rest_energies(const GarmentSimulation& sim) {
  std::vector<const RestDependentEnergy*> out{&sim.cloth()};
  if (sim.seams()) out.push_back(sim.seams());
  return out;
}

}  // namespace

SimulationDesignState::SimulationDesignState(const GarmentSimulation& sim)
    : x(flat_positions(sim)), rest(sim.garment().rest_positions()) {}

SparseMatrix exact_equilibrium_hessian(GarmentSimulation& sim) {
  EmbeddedEquilibrium& problem = sim.problem();
  SparseMatrix H = problem.hessian();
  const VecX x = flat_positions(sim);
  std::vector<Triplet> exact, projected;
  for (const RestDependentEnergy* e : rest_energies(sim)) {
    e->add_hessian(x, exact, false);
    e->add_hessian(x, projected, true);
  }
  exact.reserve(exact.size() + projected.size());
  for (const Triplet& t : projected) exact.emplace_back(t.row(), t.col(), -t.value());
  SparseMatrix difference(x.size(), x.size());
  difference.setFromTriplets(exact.begin(), exact.end());
  difference.prune(0.0);
  if (difference.nonZeros() > 0) {
    const SparseMatrix J = problem.position_jacobian();
    H += SparseMatrix(J.transpose() * difference * J);
  }
  H.makeCompressed();
  return H;
}

SparseMatrix mixed_rest_derivative(const GarmentSimulation& sim) {
  const VecX x = flat_positions(sim);
  std::vector<Triplet> t;
  for (const RestDependentEnergy* e : rest_energies(sim)) e->add_mixed_rest(x, t);
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
  const SparseMatrix H = exact_equilibrium_hessian(sim);

  if (!cholesky_.factorize(H)) {
    double mean_diag = H.diagonal().cwiseAbs().mean();
    if (!(mean_diag > 0.0) || !std::isfinite(mean_diag)) mean_diag = 1.0;
    double shift = options_.initial_regularization * mean_diag;
    SparseMatrix I(H.rows(), H.cols());
    I.setIdentity();
    bool ok = false;
    for (int k = 0; k < options_.max_regularizations && !ok; ++k) {
      ok = cholesky_.factorize(SparseMatrix(H + shift * I));
      if (!ok) shift *= options_.regularization_growth;
    }
    if (!ok)
      throw SolverError(
          "adjoint: the equilibrium Hessian could not be factorized even with "
          "diagonal shift " +
          std::to_string(shift) + " N/m");
    r.hessian_shift = shift;
  }
  const VecX lambda = cholesky_.solve(rhs);
  r.adjoint_residual = (H * lambda - rhs).norm() / rhs.norm();
  r.solved = true;
  const VecX j_lambda = J * lambda;  // 3·n_g
  r.rest_gradient -= mixed_rest_derivative(sim).transpose() * j_lambda;
  if (!r.rest_gradient.allFinite())
    throw SolverError("adjoint: the design gradient is not finite (singular equilibrium?)");
  return r;
}

}  // namespace tightfit
