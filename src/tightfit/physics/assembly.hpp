#pragma once
/// Local-to-global assembly helpers shared by the energies: an element owns a few
/// vertices, each with `Dim` consecutive degrees of freedom (DOF index Dim·vertex + k),
/// and its local gradient/Hessian is ordered vertex by vertex in the same way.
#include <array>
#include <vector>

#include <Eigen/Eigenvalues>

#include "tightfit/common/types.hpp"
#include "tightfit/physics/energy.hpp"

namespace tightfit {

/// Projects the symmetric matrix `H` onto the positive semi-definite cone in place
/// (eigen-decomposition, negative eigenvalues set to zero).
template <int N>
void project_psd(Eigen::Matrix<double, N, N>& H) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(H);
  if (eig.eigenvalues().minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, N, 1> clamped = eig.eigenvalues().cwiseMax(0.0);
  H = eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose();
}

/// g[Dim·ids[a] + k] += local[Dim·a + k].
template <int Dim, std::size_t NV>
void scatter_gradient(const std::array<int, NV>& ids,
                      const Eigen::Matrix<double, Dim* static_cast<int>(NV), 1>& local, VecX& g) {
  for (std::size_t a = 0; a < NV; ++a)
    for (int k = 0; k < Dim; ++k) g[Dim * ids[a] + k] += local[Dim * static_cast<int>(a) + k];
}

/// Writes the local block (rows: RowDim DOFs of each `rows` vertex; columns: ColDim
/// DOFs of each `cols` vertex) as RowDim·NR·ColDim·NC consecutive triplets starting at
/// `out` (an element's own slot of a preallocated array, so elements can be assembled
/// in parallel in a fixed order). Zeros are written too, so that the sparsity pattern
/// does not depend on the state (a sparse Cholesky reuses its analysis).
template <int RowDim, std::size_t NR, int ColDim, std::size_t NC, typename Derived>
void scatter_block(const std::array<int, NR>& rows, const std::array<int, NC>& cols,
                   const Eigen::MatrixBase<Derived>& local, Triplet* out) {
  for (std::size_t a = 0; a < NR; ++a)
    for (int i = 0; i < RowDim; ++i)
      for (std::size_t b = 0; b < NC; ++b)
        for (int j = 0; j < ColDim; ++j)
          *out++ =
              Triplet(RowDim * rows[a] + i, ColDim * cols[b] + j,
                      local(RowDim * static_cast<int>(a) + i, ColDim * static_cast<int>(b) + j));
}

/// Appends the local block as triplets (same order as the pointer version).
template <int RowDim, std::size_t NR, int ColDim, std::size_t NC, typename Derived>
void scatter_block(const std::array<int, NR>& rows, const std::array<int, NC>& cols,
                   const Eigen::MatrixBase<Derived>& local, std::vector<Triplet>& out) {
  const std::size_t first = out.size();
  out.resize(first + RowDim * NR * ColDim * NC);
  scatter_block<RowDim, NR, ColDim, NC>(rows, cols, local, out.data() + first);
}

/// A symmetric local Hessian over `ids` (Dim DOFs per vertex) as (Dim·NV)² triplets.
template <int Dim, std::size_t NV, typename Derived>
void scatter_hessian(const std::array<int, NV>& ids, const Eigen::MatrixBase<Derived>& local,
                     Triplet* out) {
  scatter_block<Dim, NV, Dim, NV>(ids, ids, local, out);
}

/// Appends a symmetric local Hessian over `ids` (Dim DOFs per vertex) as triplets.
template <int Dim, std::size_t NV, typename Derived>
void scatter_hessian(const std::array<int, NV>& ids, const Eigen::MatrixBase<Derived>& local,
                     std::vector<Triplet>& out) {
  scatter_block<Dim, NV, Dim, NV>(ids, ids, local, out);
}

}  // namespace tightfit
