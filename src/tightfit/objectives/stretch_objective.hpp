#pragma once
/// Stretch & compression objective (paper Sec. 5.2, Eq. 30):
///   T_stretch = Σ_e A_e Σ_{i=1,2} pen(λ_i^e),
///   pen(λ) = (λ − λ_min)² for λ < λ_min,  (λ − λ_max)² for λ > λ_max,  0 in between,
/// with λ_i^e the eigenvalues of the element's right Cauchy-Green tensor C = FᵀF
/// (SQUARED principal stretches), F = Ds Dm⁻¹ as in ClothEnergy, and A_e the element's
/// rest area (m²). T is in m² (area × squared-stretch²).
///
/// Bounds are given as principal STRETCHES s (docs/design.md §4): "30 % stretch" is s = 1.3,
/// i.e. λ = s² = 1.69. StretchBounds holds s_min and s_max; λ_min = s_min², λ_max = s_max².
/// s_max = +infinity disables the upper bound.
///
/// Derivatives are closed form: with m = (λ1+λ2)/2,
///   ∂(pen(λ1)+pen(λ2))/∂C = (pen'(λ1)+pen'(λ2))/2 · I + D · (C − m I),
///   D = (pen'(λ1) − pen'(λ2)) / (λ1 − λ2)   (→ pen''(m) when λ1 = λ2),
/// which needs no eigenvectors and stays finite at λ1 = λ2 (D ∈ [0, 2] always, and its
/// factor C − m I vanishes there). pen is C¹, so T is C¹ in x and Xbar. Depends on x
/// and Xbar (through F and A_e).
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit {

/// Admissible principal stretch range [s_min, s_max] (dimensionless, 1 = rest length).
struct StretchBounds {
  double min_stretch = 1.0;
  double max_stretch = 1.3;
};

class StretchObjective : public DesignTerm {
 public:
  /// Over all cloth triangles of the garment (Garment::pattern_triangles, positions via
  /// pattern_to_garment). Throws InputError (source "stretch objective") unless
  /// 0 < s_min <= s_max (s_max may be +infinity).
  StretchObjective(const Garment& garment, StretchBounds bounds);

  std::string name() const override { return "stretch"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }

  /// Eigenvalues (λ1 >= λ2) of C for every element at the state (for reports/tests).
  std::vector<Vec2> cauchy_green_eigenvalues(const DesignState& state) const;

  double lambda_min() const { return lambda_min_; }
  double lambda_max() const { return lambda_max_; }

 private:
  void check(const DesignState& state) const;

  Triangles triangles_;  // over pattern vertices
  std::vector<int> pattern_to_garment_;
  int num_garment_ = 0;
  int num_pattern_ = 0;
  double lambda_min_ = 1.0;
  double lambda_max_ = 1.69;
};

}  // namespace tightfit
