#pragma once
/// The one shared finite-difference checker. Every energy, objective and regularizer
/// is tested through it: gradients, Hessians and mixed derivatives are all Jacobians
/// of some map R^n -> R^m, compared against a fourth-order central difference
///   J_fd e_j = [8(F(x+h e_j) - F(x-h e_j)) - (F(x+2h e_j) - F(x-2h e_j))] / (12 h).
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace tightfit::test {

using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
using ScalarFunction = std::function<double(const Eigen::VectorXd&)>;

/// Result of a derivative check: relative error ||J - J_fd||_F / max(||J_fd||_F, floor).
struct FdCheck {
  double relative_error = 0.0;
  double analytic_norm = 0.0;
  double fd_norm = 0.0;
  Eigen::MatrixXd analytic;
  Eigen::MatrixXd numeric;
};

/// Fourth-order central-difference Jacobian of `f` at `x` (m×n), step `h`.
inline Eigen::MatrixXd fd_jacobian(const VectorFunction& f, const Eigen::VectorXd& x, double h) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  Eigen::VectorXd xp = x;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    auto eval = [&](double t) {
      xp[j] = x[j] + t;
      Eigen::VectorXd r = f(xp);
      xp[j] = x[j];
      return r;
    };
    J.col(j) = (8.0 * (eval(h) - eval(-h)) - (eval(2 * h) - eval(-2 * h))) / (12.0 * h);
  }
  return J;
}

/// Compares `analytic` (m×n) with the finite-difference Jacobian of `f` at `x`.
/// `floor` keeps the relative error meaningful when the derivative vanishes.
inline FdCheck check_jacobian(const VectorFunction& f, const Eigen::MatrixXd& analytic,
                              const Eigen::VectorXd& x, double h, double floor = 1e-12) {
  FdCheck r;
  r.analytic = analytic;
  r.numeric = fd_jacobian(f, x, h);
  r.analytic_norm = analytic.norm();
  r.fd_norm = r.numeric.norm();
  r.relative_error = (analytic - r.numeric).norm() / std::max(r.fd_norm, floor);
  return r;
}

/// Gradient check of a scalar function (gradient given as a vector).
inline FdCheck check_gradient(const ScalarFunction& f, const Eigen::VectorXd& gradient,
                              const Eigen::VectorXd& x, double h, double floor = 1e-12) {
  VectorFunction fv = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd out(1);
    out[0] = f(y);
    return out;
  };
  return check_jacobian(fv, gradient.transpose(), x, h, floor);
}

/// Hessian (or mixed derivative) check: `hessian` is the Jacobian of `gradient`.
inline FdCheck check_hessian(const VectorFunction& gradient, const Eigen::MatrixXd& hessian,
                             const Eigen::VectorXd& x, double h, double floor = 1e-12) {
  return check_jacobian(gradient, hessian, x, h, floor);
}

/// Directional-derivative check for large problems: compares g·d with the
/// fourth-order difference of f along d. Returns |analytic - fd| / max(|fd|, floor).
inline double check_directional(const ScalarFunction& f, const Eigen::VectorXd& gradient,
                                const Eigen::VectorXd& x, const Eigen::VectorXd& d, double h,
                                double floor = 1e-12) {
  auto at = [&](double t) { return f(x + t * d); };
  const double fd = (8.0 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12.0 * h);
  return std::abs(gradient.dot(d) - fd) / std::max(std::abs(fd), floor);
}

/// A reproducible random vector with entries uniform in [-1, 1].
inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

}  // namespace tightfit::test
