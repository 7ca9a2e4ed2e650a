#include "tightfit/physics/sum_energy.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace tightfit {

void SumEnergy::add(std::shared_ptr<const Energy> term, double weight) {
  if (!term) throw std::invalid_argument("SumEnergy::add: null energy");
  if (!std::isfinite(weight) || weight < 0.0)
    throw std::invalid_argument("SumEnergy::add: weight must be finite and >= 0");
  terms_.push_back({std::move(term), weight});
}

double SumEnergy::value(const VecX& x) const {
  double total = 0.0;
  for (const Term& t : terms_) {
    const double v = t.energy->value(x);
    if (v == std::numeric_limits<double>::infinity()) return v;
    total += t.weight * v;
  }
  return total;
}

void SumEnergy::add_gradient(const VecX& x, VecX& g) const {
  VecX term_gradient(g.size());
  for (const Term& t : terms_) {
    term_gradient.setZero();
    t.energy->add_gradient(x, term_gradient);
    g += t.weight * term_gradient;
  }
}

void SumEnergy::add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd) const {
  for (const Term& t : terms_) {
    const std::size_t first = H.size();
    t.energy->add_hessian(x, H, project_psd);
    if (t.weight != 1.0)
      for (std::size_t k = first; k < H.size(); ++k)
        H[k] = Triplet(H[k].row(), H[k].col(), t.weight * H[k].value());
  }
}

}  // namespace tightfit
