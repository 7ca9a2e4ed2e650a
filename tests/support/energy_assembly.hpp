#pragma once
/// One energy's gradient and Hessian as a vector and a matrix, for the tests that check
/// energies one at a time (the solvers assemble sums of energies themselves).
#include <vector>

#include "support/element_triplets.hpp"
#include "tightfit/physics/assembly.hpp"
#include "tightfit/physics/energy.hpp"

namespace tightfit::test {

/// Compressed rows×cols matrix from triplets (duplicates summed).
inline SparseMatrix sparse_from_triplets(Eigen::Index rows, Eigen::Index cols,
                                         const std::vector<Triplet>& triplets) {
  SparseMatrix m(rows, cols);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

/// dU/dx of one energy at x (same length as x).
inline VecX energy_gradient(const Energy& energy, const VecX& x) {
  VecX g = VecX::Zero(x.size());
  energy.add_gradient(x, g);
  return g;
}

/// d²U/dx² of one energy at x as a compressed n×n matrix (n = x.size()).
inline SparseMatrix energy_hessian(const Energy& energy, const VecX& x, bool project_psd = false) {
  std::vector<Triplet> t;
  energy.add_hessian(x, t, project_psd);
  return sparse_from_triplets(x.size(), x.size(), t);
}

/// Σ of the energy's element matrices at x (Energy::add_element_hessians) as a dense
/// n×n matrix; an energy that offers none gives an empty (0×0) matrix.
inline MatX element_hessian_sum(const Energy& energy, const VecX& x, bool project_psd = false) {
  std::vector<ElementMatrices> parts;
  if (!energy.add_element_hessians(x, parts, project_psd)) return MatX();
  std::vector<Triplet> t;
  for (const ElementMatrices& m : parts) append_element_triplets(m, t);
  return MatX(sparse_from_triplets(x.size(), x.size(), t));
}
}  // namespace tightfit::test
