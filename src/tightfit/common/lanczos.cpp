#include "tightfit/common/lanczos.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "tightfit/common/parallel.hpp"

namespace tightfit {
namespace {

/// A x for A symmetric with both triangles stored: entry i is column i of A dotted with
/// x, so the columns split between threads with no reduction (the same sums for any
/// thread count).
VecX symmetric_product(const SparseMatrix& A, const VecX& x) {
  if (!A.isCompressed()) {
    SparseMatrix compressed = A;
    compressed.makeCompressed();
    return symmetric_product(compressed, x);
  }
  VecX y(A.cols());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  parallel_for(A.cols(), [&](std::int64_t i) {
    double sum = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) sum += value[k] * x[inner[k]];
    y[i] = sum;
  });
  return y;
}

}  // namespace

double lowest_ritz_value(const SparseMatrix& A, const VecX& scaling, int steps) {
  const Eigen::Index n = A.rows();
  if (A.cols() != n || scaling.size() != n || steps < 1)
    throw std::invalid_argument("lowest_ritz_value: sizes or step count invalid");
  if (!(scaling.array() > 0.0).all())
    throw std::invalid_argument("lowest_ritz_value: scaling must be positive");
  if (n == 0) return 0.0;
  const VecX inv_sqrt = scaling.cwiseSqrt().cwiseInverse();
  // A fixed start vector with no structure a mode of A could be orthogonal to.
  VecX v(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v[i] = 1.0 + 0.5 * std::sin(12.9898 * static_cast<double>(i + 1));
  v.normalize();
  VecX previous = VecX::Zero(n);
  std::vector<double> alpha, beta;
  double beta_previous = 0.0;
  for (int j = 0; j < std::min<Eigen::Index>(steps, n); ++j) {
    VecX w = inv_sqrt.cwiseProduct(symmetric_product(A, inv_sqrt.cwiseProduct(v)));
    w -= beta_previous * previous;
    const double a = w.dot(v);
    w -= a * v;
    alpha.push_back(a);
    const double b = w.norm();
    if (!(b > 1e-12 * std::abs(a)) || !std::isfinite(b)) break;  // invariant subspace
    beta.push_back(b);
    previous = std::move(v);
    v = w / b;
    beta_previous = b;
  }
  const auto k = static_cast<Eigen::Index>(alpha.size());
  VecX diagonal = Eigen::Map<const VecX>(alpha.data(), k);
  VecX sub_diagonal = Eigen::Map<const VecX>(beta.data(), k - 1);
  if (k == 1) return diagonal[0];
  Eigen::SelfAdjointEigenSolver<MatX> eigen;
  eigen.computeFromTridiagonal(diagonal, sub_diagonal, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().minCoeff();
}

}  // namespace tightfit
