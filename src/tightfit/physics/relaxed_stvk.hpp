#pragma once
/// The relaxed St.Venant-Kirchhoff membrane law of tension field theory (paper Eq. 7-10),
/// smoothed so that the energy density is C² in the right Cauchy-Green tensor C.
///
/// Notation: C (2×2) = FᵀF with eigenvalues λ1 >= λ2 (squared principal stretches),
/// Green strains e_i = (λ_i - 1)/2, membrane Lamé constants λ, μ (here written α, β):
///   W_StVK = α/2 (e1+e2)² + β (e1² + e2²)                                   (Eq. 7, 8)
///   λ̄2(λ1) = (2α + 2β - αλ1)/(α + 2β)                                      (Eq. 9)
/// The three regimes of Eq. 10 combine into one formula with ramps [z]₊ = max(z, 0):
///   W_cloth = k1/2 [z1]₊² + k2/2 [z2]₊²,   z1 = e1,  z2 = e2 + ν' e1,
///   k1 = 4β(α+β)/(α+2β),  k2 = α + 2β,  ν' = α/(α+2β)
/// (z1 < 0: slack, W = 0; z1 >= 0 > z2: wrinkled, W = k1/2 e1² = β(α+β)/(2(α+2β)) (λ1-1)²,
/// which is Eq. 10's W_StVK(λ1, λ̄2(λ1)); z2 >= 0: taut, W = W_StVK since z2 = 0 ⇔ λ2 = λ̄2).
/// With the plane-stress constants of ClothMaterial, k1 = E, k2 = E/(1-ν²), ν' = ν.
///
/// Smoothing, one width δ = `regime_smoothing` (Green-strain units):
///  * each ramp square [z]₊²/2 is replaced by ρ_δ(z) whose derivative (the force) is the
///    quadratic interpolation of Skouras et al. 2014 in the band |z| < δ:
///      ρ = 0 (z <= -δ),  (z+δ)³/(12δ) (|z| < δ),  z²/2 + δ²/6 (z >= δ);
///  * e1, e2 enter through m = (e1+e2)/2 and r = sqrt(((e1-e2)/2)² + ε²), ε = δ/2, as
///    z1 = m + r, z2 = (1+ν')m - (1-ν')r, i.e. the eigenvalue gap |e1-e2| is smoothed
///    (ε = δ/2 keeps the rest state C = I inside the band, away from its edges).
///    r depends on C only through tr C and det C, so no eigen-decomposition is needed and
///    nothing is singular at λ1 = λ2 (where regimes meet at C = I, a symmetric smoothing
///    is required for C² and this one provides it).
/// Properties: C² in C everywhere; exactly zero energy and stress when z1 <= -δ (slack
/// beyond the band); exactly W_StVK + (k1+k2)δ²/6 + (k1 + k2(1-ν')²)ε²/2 (a constant)
/// when z1, z2 >= δ (taut beyond the band), so stresses there are exact StVK; in the
/// wrinkled regime z1 exceeds e1 by about ε²/|e1-e2|; converges to Eq. 10 as δ → 0.
#include <memory>

#include "tightfit/common/types.hpp"

namespace tightfit {

struct MeasuredFabric;  // physics/fabric_law.hpp

/// Cloth material (paper Sec. 6.2 defaults: pants and wetsuit fabric).
struct ClothMaterial {
  double youngs_modulus = 5.4e6;   ///< E, Pa
  double poisson_ratio = 0.33;     ///< ν, in (-1, 1)
  double thickness = 1e-4;         ///< t, m
  double regime_smoothing = 1e-3;  ///< δ > 0, Green strain; width of the regime transitions
  /// A measured orthotropic knit (physics/fabric_law.hpp) instead of E and ν; null: the
  /// isotropic relaxed StVK law. `thickness` is the measured fabric's.
  std::shared_ptr<const MeasuredFabric> measured;

  /// Plane-stress membrane Lamé λ = Eν/(1-ν²), Pa.
  double lame_lambda() const {
    return youngs_modulus * poisson_ratio / (1.0 - poisson_ratio * poisson_ratio);
  }
  /// Membrane shear modulus μ = E/(2(1+ν)), Pa.
  double lame_mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

/// Regime of Eq. 10 (unsmoothed classification by the eigenvalues of C).
enum class ClothRegime { kSlack, kWrinkled, kTaut };

/// Printable regime name ("slack", "wrinkled", "taut").
const char* regime_name(ClothRegime regime);

/// The smoothed relaxed StVK energy density as a function of the invariants
/// I1 = tr C and I2 = det C (W in J/m³ = Pa, per unit rest volume).
class RelaxedStVK {
 public:
  /// Throws InputError for E <= 0, ν outside (-1, 1), t <= 0 or δ <= 0.
  explicit RelaxedStVK(const ClothMaterial& material);

  /// W and its first and second derivatives with respect to (I1, I2).
  struct Derivatives {
    double value = 0.0;
    Vec2 gradient = Vec2::Zero();
    Mat2 hessian = Mat2::Zero();
  };
  /// `order` 0: value only; 1: value and gradient; 2: all.
  Derivatives evaluate(double i1, double i2, int order = 2) const;
  double density(double i1, double i2) const { return evaluate(i1, i2, 0).value; }

  /// Second Piola-Kirchhoff stress S = 2 ∂W/∂C (2×2, Pa) for a symmetric C.
  Mat2 second_piola(const Mat2& C) const;

  /// Unsmoothed regime of Eq. 10 for a symmetric C.
  ClothRegime regime(const Mat2& C) const;
  /// λ̄2(λ1) of Eq. 9.
  double wrinkle_threshold(double lambda1) const;

  const ClothMaterial& material() const { return material_; }

 private:
  ClothMaterial material_;
  double alpha_ = 0.0;  // Lamé λ
  double beta_ = 0.0;   // Lamé μ
  double k1_ = 0.0;
  double k2_ = 0.0;
  double nu_ = 0.0;  // ν' = α/(α+2β)
  double delta_ = 0.0;
  double epsilon_ = 0.0;  // ε = δ/2
};

/// Eigenvalues (descending) of a symmetric 2×2 matrix, closed form.
Vec2 symmetric_eigenvalues(const Mat2& A);
/// Unit eigenvector of a symmetric 2×2 matrix for its largest eigenvalue (any unit vector
/// when the eigenvalues coincide).
Vec2 symmetric_major_eigenvector(const Mat2& A);

}  // namespace tightfit
