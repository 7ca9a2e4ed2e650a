#pragma once
/// The Hessian of the embedded cloth–body system (embedded_equilibrium.hpp) held as its
/// factors, H = Jᵀ H_xx J + E:
///  * J = dx/dq, per garment vertex i: the tangents [x_u x_v] (3×2) on its own two DOFs
///    and its limit weights p_j·I (3×3) on the body vertices of its stencil;
///  * H_xx, the garment energies' Hessian in x, as 3×3 blocks per garment vertex pair;
///  * E, the body energies' 3×3 blocks plus the second-derivative terms of the embedding
///    contracted with the garment forces g_i = ∂U/∂x_i: [x_uu·g x_uv·g; x_uv·g x_vv·g] on
///    the vertex's own DOFs and (∂p_j/∂u g_i, ∂p_j/∂v g_i) between them and body vertex j.
/// matrix() assembles H as a compressed sparse matrix by a sparse triple product taken
/// column by column on DOF blocks (Gustavson's method: one dense accumulator per thread,
/// no triplets, no sort of the result, no intermediate sparse products); multiply()
/// applies H to a vector from the factors, each output entry gathered by one thread (H_xx
/// and the body Hessian are symmetric: a block column serves as the block row). Both give
/// the same values for every thread count, bit for bit.
#include <vector>

#include "tightfit/common/block_sparse_matrix.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// The factors of H at one state. DOFs are numbered garment first (two per free garment
/// vertex), then body (three per free body vertex).
struct CoupledHessianFactors {
  Eigen::Index num_dofs = 0;
  std::vector<int> garment_dof;  ///< per garment vertex: its first DOF, −1 when pinned
  std::vector<int> body_dof;     ///< per body vertex: its first DOF, −1 when pinned
  /// Stencil entries of garment vertex i: [stencil_start[i], stencil_start[i + 1]).
  std::vector<int> stencil_start;
  std::vector<int> stencil_vertex;                 ///< body vertex of each entry (unique per i)
  std::vector<double> weight, weight_u, weight_v;  ///< p_j, ∂p_j/∂u, ∂p_j/∂v per entry
  std::vector<Mat32> tangents;                     ///< per garment vertex: [x_u x_v] (m)
  std::vector<Mat2> curvature_terms;               ///< per garment vertex (N)
  Points3 garment_forces;                          ///< per garment vertex: ∂U/∂x_i (N), n_g×3
  BlockSparseMatrix3 garment;                      ///< H_xx over the garment vertices (N/m)
  BlockSparseMatrix3 body;                         ///< the body energies' Hessian over all
                                                   ///< body vertices (N/m); empty: none
};

class CoupledHessian {
 public:
  /// Throws std::invalid_argument when the DOF numbering is not garment-first or the
  /// sizes disagree.
  explicit CoupledHessian(CoupledHessianFactors factors);

  /// H (num_dofs²; both triangles; compressed). Its pattern depends only on the DOF
  /// numbering, the stencils and the block patterns of H_xx and of the body Hessian.
  SparseMatrix matrix() const;
  /// H v (num_dofs).
  VecX multiply(const VecX& v) const;

  Eigen::Index num_dofs() const { return f_.num_dofs; }

 private:
  /// One column block of H (first DOF `dof`, size 2 or 3) accumulated into `spa`.
  struct Accumulator;
  void accumulate_column(int dof, Accumulator& spa) const;
  /// Work estimate of a column block, for splitting the columns between threads.
  double column_work(int dof) const;
  int block_size(int dof) const { return dof < garment_dof_end_ ? 2 : 3; }

  CoupledHessianFactors f_;
  int garment_dof_end_ = 0;          // first body DOF
  std::vector<int> garment_of_dof_;  // per garment DOF block start: its vertex (−1 else)
  std::vector<int> body_of_dof_;     // per body DOF block start: its vertex (−1 else)
  /// Stencil entries naming body vertex a: [inverse_start_[a], inverse_start_[a + 1]) of
  /// inverse_entries_, ascending.
  std::vector<int> inverse_start_, inverse_entries_;
  std::vector<int> entry_owner_;  // garment vertex of each stencil entry
};

}  // namespace tightfit
