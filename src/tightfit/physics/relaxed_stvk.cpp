#include "tightfit/physics/relaxed_stvk.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

/// Smoothed ramp square ρ_δ(z) ≈ max(z,0)²/2 and its derivatives.
struct Ramp {
  double value, d1, d2;
};

Ramp smoothed_ramp(double z, double delta) {
  if (z <= -delta) return {0.0, 0.0, 0.0};
  if (z >= delta) return {0.5 * z * z + delta * delta / 6.0, z, 1.0};
  const double s = z + delta;
  return {s * s * s / (12.0 * delta), s * s / (4.0 * delta), s / (2.0 * delta)};
}

}  // namespace

const char* regime_name(ClothRegime regime) {
  switch (regime) {
    case ClothRegime::kSlack:
      return "slack";
    case ClothRegime::kWrinkled:
      return "wrinkled";
    case ClothRegime::kTaut:
      return "taut";
  }
  return "unknown";
}

RelaxedStVK::RelaxedStVK(const ClothMaterial& material) : material_(material) {
  if (!(material.youngs_modulus > 0.0))
    throw InputError("cloth material", "Young's modulus must be > 0");
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 1.0))
    throw InputError("cloth material", "Poisson ratio must lie in (-1, 1)");
  if (!(material.thickness > 0.0)) throw InputError("cloth material", "thickness must be > 0");
  if (!(material.regime_smoothing > 0.0) || !std::isfinite(material.regime_smoothing))
    throw InputError("cloth material", "regime smoothing width must be > 0");
  alpha_ = material.lame_lambda();
  beta_ = material.lame_mu();
  k2_ = alpha_ + 2.0 * beta_;
  k1_ = 4.0 * beta_ * (alpha_ + beta_) / k2_;
  nu_ = alpha_ / k2_;
  delta_ = material.regime_smoothing;
  epsilon_ = 0.5 * delta_;
}

RelaxedStVK::Derivatives RelaxedStVK::evaluate(double i1, double i2, int order) const {
  const double m = 0.25 * (i1 - 2.0);
  const double q = std::max((i1 * i1 - 4.0 * i2) / 16.0, 0.0) + epsilon_ * epsilon_;
  const double r = std::sqrt(q);
  const double z1 = m + r;
  const double z2 = (1.0 + nu_) * m - (1.0 - nu_) * r;
  const Ramp p1 = smoothed_ramp(z1, delta_);
  const Ramp p2 = smoothed_ramp(z2, delta_);
  Derivatives d;
  d.value = k1_ * p1.value + k2_ * p2.value;
  if (order < 1) return d;
  const Vec2 dm(0.25, 0.0);
  const Vec2 dr(i1 / (16.0 * r), -1.0 / (8.0 * r));
  const Vec2 dz1 = dm + dr;
  const Vec2 dz2 = (1.0 + nu_) * dm - (1.0 - nu_) * dr;
  d.gradient = k1_ * p1.d1 * dz1 + k2_ * p2.d1 * dz2;
  if (order < 2) return d;
  Mat2 d2r = -dr * dr.transpose();
  d2r(0, 0) += 1.0 / 16.0;
  d2r /= r;
  d.hessian = k1_ * p1.d2 * dz1 * dz1.transpose() + k2_ * p2.d2 * dz2 * dz2.transpose() +
              (k1_ * p1.d1 - k2_ * (1.0 - nu_) * p2.d1) * d2r;
  return d;
}

Mat2 RelaxedStVK::second_piola(const Mat2& C) const {
  const Derivatives d = evaluate(C.trace(), C.determinant(), 1);
  Mat2 adj;  // ∂ det C / ∂C
  adj << C(1, 1), -C(1, 0), -C(0, 1), C(0, 0);
  return 2.0 * (d.gradient[0] * Mat2::Identity() + d.gradient[1] * adj);
}

double RelaxedStVK::wrinkle_threshold(double lambda1) const {
  return (2.0 * alpha_ + 2.0 * beta_ - alpha_ * lambda1) / (alpha_ + 2.0 * beta_);
}

ClothRegime RelaxedStVK::regime(const Mat2& C) const {
  const Vec2 ev = symmetric_eigenvalues(C);
  if (ev[0] < 1.0) return ClothRegime::kSlack;
  if (ev[1] < wrinkle_threshold(ev[0])) return ClothRegime::kWrinkled;
  return ClothRegime::kTaut;
}

Vec2 symmetric_eigenvalues(const Mat2& A) {
  const double mean = 0.5 * (A(0, 0) + A(1, 1));
  const double half_diff = 0.5 * (A(0, 0) - A(1, 1));
  const double off = 0.5 * (A(0, 1) + A(1, 0));
  const double radius = std::hypot(half_diff, off);
  return Vec2(mean + radius, mean - radius);
}

Vec2 symmetric_major_eigenvector(const Mat2& A) {
  const double half_diff = 0.5 * (A(0, 0) - A(1, 1));
  const double off = 0.5 * (A(0, 1) + A(1, 0));
  if (half_diff == 0.0 && off == 0.0) return Vec2::UnitX();
  // The major axis makes the angle θ/2 with x, where (cos θ, sin θ) ∝ (half_diff, off).
  const double angle = 0.5 * std::atan2(off, half_diff);
  return Vec2(std::cos(angle), std::sin(angle));
}

}  // namespace tightfit
