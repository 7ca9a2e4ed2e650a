#pragma once
/// Stiff springs pinning chosen vertices to given 3D targets:
///   U = k/2 Σ_i |x_{v_i} - target_i|²,   k in N/m.
#include <vector>

#include "tightfit/physics/energy.hpp"

namespace tightfit {

class PinEnergy : public Energy {
 public:
  /// `vertices` (ids into x, each 3 DOFs), `targets` one row per vertex (m),
  /// `stiffness` k > 0 (N/m). Throws InputError on a size mismatch, a negative index or
  /// k <= 0.
  PinEnergy(std::vector<int> vertices, Points3 targets, double stiffness);

  std::string name() const override { return "pins"; }
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;

  /// Moves the targets (same number of rows).
  void set_targets(const Points3& targets);
  const std::vector<int>& vertices() const { return vertices_; }
  const Points3& targets() const { return targets_; }
  double stiffness() const { return stiffness_; }

 private:
  void check_x(const VecX& x) const;

  std::vector<int> vertices_;
  Points3 targets_;
  double stiffness_ = 0.0;
};

}  // namespace tightfit
