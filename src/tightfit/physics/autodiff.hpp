#pragma once
/// Forward-mode automatic differentiation for per-element kernels templated on the
/// scalar (the mid-edge shape operator and element pressure kernels of this layer, the
/// pressure and seam-traction objectives): Eigen's AutoDiffScalar with a fixed number of
/// derivative directions, plus the chain rule through the cloth law (whose derivatives
/// are known in closed form). Every helper also takes plain double, so one template
/// serves both the value (S = double) and its derivatives (S = Scalar<N>).
#include <array>
#include <cmath>
#include <type_traits>

#include <unsupported/Eigen/AutoDiff>

#include "tightfit/common/types.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"

namespace tightfit::autodiff {

/// A scalar carrying N partial derivatives.
template <int N>
using Scalar = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

template <typename S>
using Vec3T = Eigen::Matrix<S, 3, 1>;
template <typename S>
using Vec2T = Eigen::Matrix<S, 2, 1>;
template <typename S>
using Mat2T = Eigen::Matrix<S, 2, 2>;
template <typename S>
using Mat3T = Eigen::Matrix<S, 3, 3>;
template <typename S>
using Mat32T = Eigen::Matrix<S, 3, 2>;

inline double value_of(double v) { return v; }
template <int N>
double value_of(const Scalar<N>& v) {
  return v.value();
}

/// The independent variable number `index` with value `v`.
template <int N>
Scalar<N> variable(double v, int index) {
  return Scalar<N>(v, N, index);
}

/// A scalar g(I1, I2) known by its value and partials (a, b) at the value of (i1, i2),
/// chained to i1, i2's own derivatives.
inline double chain(double v, double /*a*/, double /*b*/, double /*i1*/, double /*i2*/) {
  return v;
}
template <int N>
Scalar<N> chain(double v, double a, double b, const Scalar<N>& i1, const Scalar<N>& i2) {
  return Scalar<N>(v, a * i1.derivatives() + b * i2.derivatives());
}

/// Inverse of a 2×2 matrix (closed form).
template <typename S>
Mat2T<S> inverse2(const Mat2T<S>& m) {
  const S det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  Mat2T<S> inv;
  inv << m(1, 1) / det, -m(0, 1) / det, -m(1, 0) / det, m(0, 0) / det;
  return inv;
}

/// Second Piola-Kirchhoff stress S = 2 ∂W/∂C = 2 (W_1 I + W_2 adj C) (2×2, Pa) of the
/// relaxed StVK law at the symmetric 2×2 C (same formula as RelaxedStVK::second_piola),
/// differentiable in C. With S = double only the law's gradient is evaluated.
template <typename S>
Mat2T<S> second_piola(const RelaxedStVK& law, const Mat2T<S>& c) {
  const S i1 = c(0, 0) + c(1, 1);
  const S i2 = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  const RelaxedStVK::Derivatives d =
      law.evaluate(value_of(i1), value_of(i2), std::is_same_v<S, double> ? 1 : 2);
  const S w1 = chain(d.gradient[0], d.hessian(0, 0), d.hessian(0, 1), i1, i2);
  const S w2 = chain(d.gradient[1], d.hessian(1, 0), d.hessian(1, 1), i1, i2);
  Mat2T<S> s;
  s(0, 0) = 2.0 * (w1 + w2 * c(1, 1));
  s(1, 1) = 2.0 * (w1 + w2 * c(0, 0));
  s(0, 1) = -2.0 * w2 * c(1, 0);
  s(1, 0) = -2.0 * w2 * c(0, 1);
  return s;
}

/// S = 2 ∂W/∂C (2×2, Pa) of a fabric law (fabric_law.hpp) at the symmetric 2×2 C in the
/// material frame, differentiable in C: the isotropic law as above; the measured law from
/// its gradient in c = (C_xx, C_yy, C_xy) (S_xx = 2 W_xx, S_yy = 2 W_yy, S_xy = W_xy),
/// chained through its closed-form Hessian.
template <typename S>
Mat2T<S> second_piola(const FabricLaw& law, const Mat2T<S>& c) {
  if (!law.measured()) return second_piola<S>(law.isotropic(), c);
  const Vec3 cv(value_of(c(0, 0)), value_of(c(1, 1)),
                0.5 * (value_of(c(0, 1)) + value_of(c(1, 0))));
  const FabricLaw::Derivatives d = law.evaluate(cv, std::is_same_v<S, double> ? 1 : 2);
  std::array<S, 3> g;
  if constexpr (std::is_same_v<S, double>) {
    for (int k = 0; k < 3; ++k) g[k] = d.gradient[k];
  } else {
    const std::array<S, 3> comp = {c(0, 0), c(1, 1), S(0.5 * (c(0, 1) + c(1, 0)))};
    for (int k = 0; k < 3; ++k) {
      auto derivs =
          (d.hessian(k, 0) * comp[0].derivatives() + d.hessian(k, 1) * comp[1].derivatives() +
           d.hessian(k, 2) * comp[2].derivatives())
              .eval();
      g[k] = S(d.gradient[k], derivs);
    }
  }
  Mat2T<S> s;
  s(0, 0) = 2.0 * g[0];
  s(1, 1) = 2.0 * g[1];
  s(0, 1) = g[2];
  s(1, 0) = g[2];
  return s;
}

}  // namespace tightfit::autodiff
