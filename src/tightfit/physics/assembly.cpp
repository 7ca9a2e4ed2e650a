#include "tightfit/physics/assembly.hpp"

namespace tightfit {

SparseMatrix sparse_from_triplets(Eigen::Index rows, Eigen::Index cols,
                                  const std::vector<Triplet>& triplets) {
  SparseMatrix m(rows, cols);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

VecX energy_gradient(const Energy& energy, const VecX& x) {
  VecX g = VecX::Zero(x.size());
  energy.add_gradient(x, g);
  return g;
}

SparseMatrix energy_hessian(const Energy& energy, const VecX& x, bool project_psd) {
  std::vector<Triplet> t;
  energy.add_hessian(x, t, project_psd);
  return sparse_from_triplets(x.size(), x.size(), t);
}

}  // namespace tightfit
