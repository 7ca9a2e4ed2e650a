#include "tightfit/physics/fabric_curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tightfit {
namespace {

/// 8-point Gauss–Legendre rule on [-1, 1]: exact for polynomials of degree ≤ 15 (the
/// tension in the compression band is a cubic of the quartic ramp: degree 12).
constexpr std::array<double, 4> kGaussNodes = {0.1834346424956498, 0.5255324099163290,
                                               0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kGaussWeights = {0.3626837833783620, 0.3137066458778873,
                                                 0.2223810344533745, 0.1012285362903763};

void check_points(const std::vector<double>& strain, const std::vector<double>& tension) {
  if (strain.size() != tension.size())
    throw std::invalid_argument("strain has " + std::to_string(strain.size()) +
                                " points but tension_n_per_m has " +
                                std::to_string(tension.size()));
  if (strain.size() < 2)
    throw std::invalid_argument("a curve needs at least two points, it has " +
                                std::to_string(strain.size()));
  for (std::size_t k = 0; k < strain.size(); ++k) {
    const std::string at = " (point " + std::to_string(k) + ")";
    if (!std::isfinite(strain[k]) || strain[k] < 0.0)
      throw std::invalid_argument("strain must be finite and >= 0" + at);
    if (!std::isfinite(tension[k]) || tension[k] < 0.0)
      throw std::invalid_argument("tension_n_per_m must be finite and >= 0" + at);
    if (k > 0 && !(strain[k] > strain[k - 1]))
      throw std::invalid_argument("strain must be strictly increasing" + at);
    if (k > 0 && !(tension[k] > tension[k - 1]))
      throw std::invalid_argument("tension_n_per_m must be strictly increasing" + at);
  }
  if (strain[0] == 0.0 && tension[0] != 0.0)
    throw std::invalid_argument("the tension at strain 0 must be 0 (point 0)");
  if (strain.back() > 20.0)
    throw std::invalid_argument("strain above 20 (2000 %) is not a fabric strain (point " +
                                std::to_string(strain.size() - 1) + ")");
}

}  // namespace

SmoothRamp smooth_ramp(double strain, double width) {
  if (strain <= -width) return {};
  if (strain >= width) return {strain, 1.0, 0.0};
  const double t = strain / width;
  return {0.25 * width * (1.5 * t * t - 0.25 * t * t * t * t + 2.0 * t + 0.75),
          0.25 * (3.0 * t - t * t * t + 2.0), 0.75 * (1.0 - t * t) / width,
          -1.5 * t / (width * width)};
}

FabricCurve::FabricCurve(std::vector<double> strain, std::vector<double> tension_n_per_m,
                         double smoothing) {
  check_points(strain, tension_n_per_m);
  if (!(smoothing > 0.0) || !std::isfinite(smoothing))
    throw std::invalid_argument("the smoothing width must be > 0");
  if (strain[0] > 0.0) {
    strain.insert(strain.begin(), 0.0);
    tension_n_per_m.insert(tension_n_per_m.begin(), 0.0);
  }
  strain_ = std::move(strain);
  tension_ = std::move(tension_n_per_m);
  delta_ = std::min(smoothing, 0.5 * strain_[1]);

  const std::size_t n = strain_.size();
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = strain_[k + 1] - strain_[k];
    d[k] = (tension_[k + 1] - tension_[k]) / h[k];
  }
  slope_.assign(n, 0.0);
  slope_[n - 1] = d[n - 2];
  if (n == 2) {
    slope_[0] = d[0];
  } else {
    // Interior: Fritsch–Butland weighted harmonic mean (all secants are positive).
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double w1 = 2.0 * h[k] + h[k - 1];
      const double w2 = h[k] + 2.0 * h[k - 1];
      slope_[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
    }
    // First point: the three-point PCHIP slope, limited to keep the curve monotone.
    double m0 = ((2.0 * h[0] + h[1]) * d[0] - h[0] * d[1]) / (h[0] + h[1]);
    if (m0 < 0.0) m0 = 0.0;
    if (m0 > 3.0 * d[0]) m0 = 3.0 * d[0];
    slope_[0] = m0;
    // The last slope is the last secant; the slope before it must leave the last
    // segment monotone (Fritsch–Carlson: α² + β² ≤ 9 with β = 1).
    slope_[n - 2] = std::min(slope_[n - 2], 2.8 * d[n - 2]);
  }
  cumulative_.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k)
    cumulative_[k + 1] = cumulative_[k] + h[k] * (0.5 * (tension_[k] + tension_[k + 1]) +
                                                  h[k] * (slope_[k] - slope_[k + 1]) / 12.0);
  // w(δ): the compression band's energy, ∫_{−δ}^{δ} T̃(s(ε)) dε.
  double band = 0.0;
  for (std::size_t q = 0; q < kGaussNodes.size(); ++q)
    for (const double sign : {-1.0, 1.0}) {
      const double e = sign * kGaussNodes[q] * delta_;
      band += kGaussWeights[q] * delta_ * interpolant(smooth_ramp(e, delta_).value, 1).tension;
    }
  band_energy_ = band;
}

FabricCurve::Evaluation FabricCurve::interpolant(double strain, int order) const {
  const std::size_t n = strain_.size();
  Evaluation out;
  if (strain >= strain_[n - 1]) {
    const double e = strain - strain_[n - 1];
    out.tension = tension_[n - 1] + slope_[n - 1] * e;
    out.stiffness = slope_[n - 1];
    out.energy = cumulative_[n - 1] + e * (tension_[n - 1] + 0.5 * slope_[n - 1] * e);
    return out;
  }
  const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(strain_.begin(), strain_.end(), strain) - strain_.begin() - 1);
  const double h = strain_[k + 1] - strain_[k];
  const double t = (strain - strain_[k]) / h;
  const double y0 = tension_[k], y1 = tension_[k + 1];
  const double m0 = h * slope_[k], m1 = h * slope_[k + 1];
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  out.energy = cumulative_[k] +
               h * (y0 * (0.5 * t4 - t3 + t) + m0 * (0.25 * t4 - 2.0 * t3 / 3.0 + 0.5 * t2) +
                    y1 * (-0.5 * t4 + t3) + m1 * (0.25 * t4 - t3 / 3.0));
  if (order < 1) return out;
  out.tension = y0 * (2.0 * t3 - 3.0 * t2 + 1.0) + m0 * (t3 - 2.0 * t2 + t) +
                y1 * (-2.0 * t3 + 3.0 * t2) + m1 * (t3 - t2);
  if (order < 2) return out;
  out.stiffness = (y0 * (6.0 * t2 - 6.0 * t) + m0 * (3.0 * t2 - 4.0 * t + 1.0) +
                   y1 * (-6.0 * t2 + 6.0 * t) + m1 * (3.0 * t2 - 2.0 * t)) /
                  h;
  return out;
}

FabricCurve::Evaluation FabricCurve::evaluate(double strain, int order) const {
  if (strain <= -delta_) return {};
  if (strain >= delta_) {
    Evaluation out = interpolant(strain, order);
    out.energy += band_energy_ - interpolant(delta_, 0).energy;
    return out;
  }
  const SmoothRamp r = smooth_ramp(strain, delta_);
  Evaluation out;
  // ∫_{−δ}^{ε} T̃(s(τ)) dτ by the Gauss rule on [−δ, ε].
  const double half = 0.5 * (strain + delta_), mid = 0.5 * (strain - delta_);
  for (std::size_t q = 0; q < kGaussNodes.size(); ++q)
    for (const double sign : {-1.0, 1.0}) {
      const double e = mid + sign * kGaussNodes[q] * half;
      out.energy += kGaussWeights[q] * half * interpolant(smooth_ramp(e, delta_).value, 1).tension;
    }
  if (order < 1) return out;
  const Evaluation at = interpolant(r.value, order);
  out.tension = at.tension;
  out.stiffness = at.stiffness * r.d1;
  return out;
}

}  // namespace tightfit
