#pragma once
/// An energy U(x, Xbar) that also depends on the 2D rest positions Xbar of the pattern
/// vertices (cloth and seam springs). Xbar is n_p×2 (m); as a flat vector its DOF index
/// is 2·p + k. These derivatives feed the adjoint design gradient (docs/design.md §4:
/// ∂g/∂p = (∂²U/∂q∂Xbar) W).
#include <vector>

#include "tightfit/physics/energy.hpp"

namespace tightfit {

class RestDependentEnergy : public Energy {
 public:
  /// Number of pattern vertices n_p (rows of Xbar).
  virtual int num_pattern_vertices() const = 0;
  /// Current rest positions Xbar (n_p×2, m).
  virtual const Points2& rest() const = 0;
  /// Replaces Xbar (same n_p). Throws InputError when an element becomes degenerate.
  virtual void set_rest(const Points2& rest) = 0;
  /// g_rest += ∂U/∂Xbar (J/m, length 2·n_p) at positions x.
  virtual void add_gradient_rest(const VecX& x, VecX& g_rest) const = 0;
  /// Adds ∂²U/∂x∂Xbar (N/m) as triplets: rows index x (3·n_garment), columns index
  /// Xbar (2·n_p).
  virtual void add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const = 0;
};

}  // namespace tightfit
