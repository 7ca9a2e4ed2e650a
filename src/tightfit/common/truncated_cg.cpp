#include "tightfit/common/truncated_cg.hpp"

#include <stdexcept>

namespace tightfit {

VecX truncated_cg(const LinearOperator& A, const LinearOperator& preconditioner, const VecX& b,
                  TruncatedCgReport& report, const TruncatedCgOptions& options) {
  if (!(options.relative_tolerance > 0.0) || options.max_iterations < 1)
    throw std::invalid_argument("truncated_cg: invalid options");
  report = {};
  const double b_norm = b.norm();
  VecX x = VecX::Zero(b.size());
  if (b_norm == 0.0) {
    report.converged = true;
    return x;
  }
  VecX r = b;
  VecX z = preconditioner(r);
  VecX p = z;
  double rz = r.dot(z);
  while (report.iterations < options.max_iterations) {
    const VecX Ap = A(p);
    ++report.iterations;
    const double curvature = p.dot(Ap);
    if (!(curvature > 0.0)) {
      report.negative_curvature = true;
      if (report.iterations == 1) {
        x = z;  // the preconditioned direction
        r = b - A(x);
        ++report.iterations;
      }
      break;
    }
    const double alpha = rz / curvature;
    x += alpha * p;
    r -= alpha * Ap;
    if (r.norm() <= options.relative_tolerance * b_norm) {
      report.converged = true;
      break;
    }
    z = preconditioner(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  report.relative_residual = r.norm() / b_norm;
  return x;
}

}  // namespace tightfit
