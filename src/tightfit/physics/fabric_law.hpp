#pragma once
/// The membrane law of a garment's fabric, in the material frame of its pieces: every
/// piece lies in its grain frame (garment/pattern_builder.hpp), so the pattern x axis runs
/// across the grain (the course of a knit) and the y axis along it (the wale).
///
/// Two laws share one interface, the energy density W (Pa, per unit rest volume) as a
/// function of the right Cauchy–Green tensor C = FᵀF in that frame, written
/// c = (C_xx, C_yy, C_xy):
///  * the isotropic relaxed StVK law (relaxed_stvk.hpp), the default;
///  * a measured orthotropic knit (MeasuredFabric below), from strip-test curves:
///      t W = w_course(ε_x) + w_wale(ε_y) + κ s(ε_x) s(ε_y) + G C_xy² r(ε_x, ε_y) / 2,
///      ε_x = √C_xx − 1, ε_y = √C_yy − 1 (engineering strains of the two directions),
///    w the strip energies of the curves (fabric_curve.hpp: ∂w/∂ε = T, the measured
///    tension per unit rest width), s their C² compression ramp, κ = c √(k_course k_wale)
///    the lateral coupling (c in [0, 1), k the curves' initial secant stiffnesses: the
///    quadratic form of the small-strain law stays positive definite) and G the in-plane
///    shear stiffness (N/m). A strip pulled along one direction with the other free
///    (c = 0) carries exactly the measured T; both directions are tension-only (no
///    compression below −δ), and the shear is relaxed with them: r = h_x + h_y − h_x h_y,
///    h = s'(ε) (1 for ε ≥ δ, 0 for ε ≤ −δ), so a slack knit (both directions below
///    −δ) carries nothing at all, a wrinkled one (one direction stretched) keeps its
///    shear stiffness (without it, sliding along the slack direction would cost nothing).
#include <memory>
#include <optional>
#include <string>

#include "tightfit/common/types.hpp"
#include "tightfit/physics/fabric_curve.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"

namespace tightfit {

/// A knit characterised by strip tests in its two directions (the scene's
/// "fabric": {"model": "measured", ...}, scene/fabric_spec.hpp).
struct MeasuredFabric {
  std::string name;
  FabricCurve wale;    ///< along the grain (loading)
  FabricCurve course;  ///< across the grain (loading)
  /// Unloading branches (hysteresis): when given, the worn garment sits on them.
  std::optional<FabricCurve> wale_unloading;
  std::optional<FabricCurve> course_unloading;
  double coupling = 0.0;       ///< c in [0, 1)
  double shear_n_per_m = 0.0;  ///< G > 0, N/m

  /// The curves a worn garment follows: the unloading branch when measured, else loading.
  const FabricCurve& worn_wale() const { return wale_unloading ? *wale_unloading : wale; }
  const FabricCurve& worn_course() const { return course_unloading ? *course_unloading : course; }
};

class FabricLaw {
 public:
  /// The law of `material`: measured when material.measured is set, else relaxed StVK
  /// (whose constructor checks E, ν, t, δ). Throws InputError for a thickness <= 0 or a
  /// coupling outside [0, 1) or a shear stiffness <= 0.
  explicit FabricLaw(const ClothMaterial& material);

  /// W and its derivatives with respect to c = (C_xx, C_yy, C_xy) (C_xy one variable
  /// standing for both off-diagonal entries).
  struct Derivatives {
    double value = 0.0;
    Vec3 gradient = Vec3::Zero();
    Mat3 hessian = Mat3::Zero();
  };
  /// `order` 0: value only; 1: value and gradient; 2: all.
  Derivatives evaluate(const Vec3& c, int order = 2) const;
  /// Second Piola-Kirchhoff stress S = 2 ∂W/∂C (2×2, Pa) at a symmetric C.
  Mat2 second_piola(const Mat2& C) const;

  /// Regime at a symmetric C: the isotropic law's (Eq. 10); for a measured knit, taut
  /// when both material directions are stretched, wrinkled when one is, slack otherwise.
  ClothRegime regime(const Mat2& C) const;

  /// A characteristic membrane stiffness (N/m), for solver tolerances: E t for the
  /// isotropic law; for a measured knit the geometric mean of the worn course and wale
  /// curves' secant stiffnesses at their last measured points.
  double reference_stiffness() const;

  /// Whether the law is a measured orthotropic knit (else isotropic relaxed StVK).
  bool measured() const { return material_.measured != nullptr; }
  const ClothMaterial& material() const { return material_; }
  /// The isotropic law (its defaults when the fabric is measured).
  const RelaxedStVK& isotropic() const { return isotropic_; }

 private:
  ClothMaterial material_;
  RelaxedStVK isotropic_;
  double coupling_ = 0.0;  // κ = c √(k_course k_wale), N/m
};

/// Components (C_xx, C_yy, C_xy) of a symmetric 2×2 matrix.
inline Vec3 strain_components(const Mat2& C) {
  return {C(0, 0), C(1, 1), 0.5 * (C(0, 1) + C(1, 0))};
}

}  // namespace tightfit
