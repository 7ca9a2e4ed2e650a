#include "tightfit/common/preconditioned_gmres.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

namespace tightfit {

GmresReport preconditioned_gmres(const LinearOperator& A, const LinearOperator& preconditioner,
                                 const VecX& b, VecX& x, const GmresOptions& options) {
  if (options.restart < 1 || options.max_iterations < 0 || !(options.relative_tolerance > 0.0))
    throw std::invalid_argument("preconditioned_gmres: invalid options");
  const Eigen::Index n = b.size();
  if (x.size() != n) x = VecX::Zero(n);
  GmresReport report;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero();
    report.converged = true;
    return report;
  }
  const double target = options.relative_tolerance * b_norm;
  const int m = options.restart;

  std::vector<VecX> basis(static_cast<size_t>(m) + 1);
  MatX h = MatX::Zero(m + 1, m);
  VecX cs(m), sn(m), g(m + 1);
  for (;;) {
    const VecX r = b - A(x);
    const double beta = r.norm();
    report.relative_residual = beta / b_norm;
    if (beta <= target) {
      report.converged = true;
      return report;
    }
    if (report.iterations >= options.max_iterations || !std::isfinite(beta)) return report;

    basis[0] = r / beta;
    h.setZero();
    g.setZero();
    g[0] = beta;
    int k = 0;  // columns of the Hessenberg matrix filled in this cycle
    while (k < m && report.iterations < options.max_iterations) {
      VecX w = A(preconditioner(basis[static_cast<size_t>(k)]));
      ++report.iterations;
      // Modified Gram-Schmidt, twice (the second pass restores orthogonality lost to
      // round-off when w is nearly in the span of the basis).
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i <= k; ++i) {
          const double c = basis[static_cast<size_t>(i)].dot(w);
          h(i, k) += c;
          w -= c * basis[static_cast<size_t>(i)];
        }
      h(k + 1, k) = w.norm();
      for (int i = 0; i < k; ++i) {  // earlier Givens rotations on the new column
        const double t = cs[i] * h(i, k) + sn[i] * h(i + 1, k);
        h(i + 1, k) = -sn[i] * h(i, k) + cs[i] * h(i + 1, k);
        h(i, k) = t;
      }
      const double rho = std::hypot(h(k, k), h(k + 1, k));
      const bool breakdown = !(h(k + 1, k) > 0.0);
      if (!breakdown) basis[static_cast<size_t>(k) + 1] = w / h(k + 1, k);
      cs[k] = rho > 0.0 ? h(k, k) / rho : 1.0;
      sn[k] = rho > 0.0 ? h(k + 1, k) / rho : 0.0;
      h(k, k) = rho;
      h(k + 1, k) = 0.0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      ++k;
      if (std::abs(g[k]) <= target || breakdown) break;
    }
    // x += M⁻¹ V y with H y = g (upper triangular k×k).
    VecX y = g.head(k);
    for (int i = k - 1; i >= 0; --i) {
      for (int j = i + 1; j < k; ++j) y[i] -= h(i, j) * y[j];
      y[i] = h(i, i) != 0.0 ? y[i] / h(i, i) : 0.0;
    }
    VecX update = VecX::Zero(n);
    for (int i = 0; i < k; ++i) update += y[i] * basis[static_cast<size_t>(i)];
    x += preconditioner(update);
  }
}

}  // namespace tightfit
