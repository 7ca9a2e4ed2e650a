#include "tightfit/physics/pin_energy.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {

PinEnergy::PinEnergy(std::vector<int> vertices, Points3 targets, double stiffness)
    : vertices_(std::move(vertices)), targets_(std::move(targets)), stiffness_(stiffness) {
  if (static_cast<Eigen::Index>(vertices_.size()) != targets_.rows())
    throw InputError("pins", std::to_string(vertices_.size()) + " pinned vertices but " +
                                 std::to_string(targets_.rows()) + " targets");
  if (std::any_of(vertices_.begin(), vertices_.end(), [](int v) { return v < 0; }))
    throw InputError("pins", "negative vertex index");
  if (!(stiffness_ > 0.0)) throw InputError("pins", "stiffness must be > 0 (N/m)");
}

void PinEnergy::set_targets(const Points3& targets) {
  if (targets.rows() != targets_.rows())
    throw InputError("pins", "target count changed from " + std::to_string(targets_.rows()) +
                                 " to " + std::to_string(targets.rows()));
  targets_ = targets;
}

void PinEnergy::check_x(const VecX& x) const {
  for (int v : vertices_)
    if (3 * static_cast<Eigen::Index>(v) + 2 >= x.size())
      throw std::invalid_argument("PinEnergy: vertex " + std::to_string(v) +
                                  " outside the position vector");
}

double PinEnergy::value(const VecX& x) const {
  check_x(x);
  double total = 0.0;
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    total += (x.segment<3>(3 * vertices_[i]) - targets_.row(i).transpose()).squaredNorm();
  return 0.5 * stiffness_ * total;
}

void PinEnergy::add_gradient(const VecX& x, VecX& g) const {
  check_x(x);
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    g.segment<3>(3 * vertices_[i]) +=
        stiffness_ * (x.segment<3>(3 * vertices_[i]) - targets_.row(i).transpose());
}

void PinEnergy::add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd) const {
  (void)project_psd;  // the local Hessians k·I are already positive definite
  check_x(x);
  for (int v : vertices_)
    for (int k = 0; k < 3; ++k) H.emplace_back(3 * v + k, 3 * v + k, stiffness_);
}

}  // namespace tightfit
