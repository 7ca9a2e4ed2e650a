#pragma once
/// A weighted sum of energies over the same position vector x.
#include <memory>
#include <vector>

#include "tightfit/physics/energy.hpp"

namespace tightfit {

class SumEnergy : public Energy {
 public:
  /// Adds `weight`·term to the sum. The term is shared, not copied.
  void add(std::shared_ptr<const Energy> term, double weight = 1.0);

  int num_terms() const { return static_cast<int>(terms_.size()); }
  const Energy& term(int i) const { return *terms_[i].energy; }
  double weight(int i) const { return terms_[i].weight; }

  std::string name() const override { return "sum"; }
  /// Σ w_i U_i(x); +infinity as soon as one term is +infinity.
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  /// Each term's elements are projected separately when `project_psd` is set.
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;

 private:
  struct Term {
    std::shared_ptr<const Energy> energy;
    double weight;
  };
  std::vector<Term> terms_;
};

}  // namespace tightfit
