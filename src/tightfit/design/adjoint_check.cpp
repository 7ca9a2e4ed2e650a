#include "tightfit/design/adjoint_check.hpp"

#include <cmath>
#include <random>

#include "tightfit/common/error.hpp"

namespace tightfit {

VecX random_design_direction(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  VecX d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = normal(rng);
  double m = 0.0;
  for (Eigen::Index i = 0; i + 1 < n; i += 2) m = std::max(m, std::hypot(d[i], d[i + 1]));
  return m > 0.0 ? VecX(d / m) : d;
}

std::vector<DirectionalCheck> check_design_gradient(DesignProblem& problem, const VecX& p,
                                                    const GradientCheckOptions& options) {
  const DesignEvaluation base = problem.evaluate(p, true);
  if (!base.ok) throw SolverError("gradient check: cannot evaluate the pattern: " + base.failure);
  problem.accept();
  const double h = options.step > 0.0 ? options.step : 1e-5 * problem.mean_boundary_edge();
  auto value = [&](const VecX& q) {
    const DesignEvaluation e = problem.evaluate(q, false);
    if (!e.ok)
      throw SolverError("gradient check: a finite-difference sample failed (step " +
                        std::to_string(h) + " m): " + e.failure);
    return e.value;
  };
  std::vector<DirectionalCheck> out;
  for (int k = 0; k < options.directions; ++k) {
    const VecX d = random_design_direction(p.size(), options.seed + static_cast<unsigned>(k));
    DirectionalCheck c;
    c.adjoint = base.gradient.dot(d);
    c.finite_difference = (8.0 * (value(p + h * d) - value(p - h * d)) -
                           (value(p + 2 * h * d) - value(p - 2 * h * d))) /
                          (12.0 * h);
    const double diff = std::abs(c.adjoint - c.finite_difference);
    c.relative_error = c.finite_difference != 0.0 ? diff / std::abs(c.finite_difference) : diff;
    c.hessian_shift = base.hessian_shift;
    out.push_back(c);
  }
  problem.restore_accepted();
  return out;
}

}  // namespace tightfit
