#pragma once
/// The element pressure kernel of the generalized Young-Laplace equation (paper Eq. 31),
/// templated on the scalar S: double for the fit analysis (cloth_analysis.hpp),
/// autodiff::Scalar<N> for the exact derivatives of the pressure objective.
///   σ = F S Fᵀ / J   (Cauchy stress, 3×3, Pa),   T = t σ   (membrane tension, N/m),
///   p = tr(T Λ) = t tr(σ Λ)   (Pa),
/// with F the 3×2 deformation gradient of a cloth element, S = 2 ∂W/∂C the second
/// Piola-Kirchhoff stress of the fabric law (fabric_law.hpp, in the piece's grain frame) at C =
/// FᵀF, J = √det C the area ratio, t the rest thickness (m) and Λ the element's 3×3 world-frame
/// shape operator (1/m; e.g. mid_edge_kernel.hpp). p is positive when the fabric presses onto a
/// convex body (outward normals).
#include <optional>
#include <utility>

#include "tightfit/physics/autodiff.hpp"
#include "tightfit/physics/fabric_law.hpp"

namespace tightfit {

/// Elements whose area ratio J = √det C is not above this are degenerate (no stress).
inline constexpr double kMinElementAreaRatio = 1e-12;

/// Cauchy stress σ = F S Fᵀ / J (3×3 symmetric, Pa, tangent to the element) of the
/// relaxed law for the deformation gradient `F` (3×2). Returns nothing for a degenerate
/// element (J ≤ kMinElementAreaRatio).
template <typename S>
std::optional<autodiff::Mat3T<S>> cauchy_stress(const FabricLaw& law,
                                                const autodiff::Mat32T<S>& F) {
  using autodiff::value_of;
  using std::sqrt;
  const autodiff::Mat2T<S> c = F.transpose() * F;
  const S det_c = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  if (!(value_of(det_c) > kMinElementAreaRatio * kMinElementAreaRatio)) return std::nullopt;
  const S J = sqrt(det_c);
  return std::optional<autodiff::Mat3T<S>>(
      std::in_place, F * autodiff::second_piola<S>(law, c) * F.transpose() / J);
}

/// Young-Laplace pressure p = tr(T Λ) (Pa) of an element with membrane tension `tension`
/// (T = t σ, 3×3 symmetric, N/m) on a surface with shape operator `lambda` (3×3, 1/m).
/// Linear in T: t · young_laplace_pressure(σ, Λ) is the same pressure.
template <typename S>
S young_laplace_pressure(const autodiff::Mat3T<S>& tension, const autodiff::Mat3T<S>& lambda) {
  return tension.cwiseProduct(lambda).sum();
}

/// p = t tr(σ Λ) (Pa) of an element with deformation gradient `F` (3×2) and shape
/// operator `lambda` (3×3, 1/m), t = law.material().thickness. Returns nothing for a
/// degenerate element (see cauchy_stress).
template <typename S>
std::optional<S> element_pressure(const FabricLaw& law, const autodiff::Mat32T<S>& F,
                                  const autodiff::Mat3T<S>& lambda) {
  const std::optional<autodiff::Mat3T<S>> sigma = cauchy_stress<S>(law, F);
  if (!sigma) return std::nullopt;
  return law.material().thickness * young_laplace_pressure<S>(*sigma, lambda);  // t tr(σ Λ)
}

}  // namespace tightfit
