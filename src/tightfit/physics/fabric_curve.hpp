#pragma once
/// A measured strip-test curve of a knit: tension per unit rest width T (N/m) of a
/// uniaxial strip against its engineering strain ε = λ − 1 (dimensionless), as a
/// tensile tester reports it (EN ISO 13934-1, ASTM D4964).
///
/// Interpolation. The points are joined by a monotone piecewise cubic Hermite curve
/// T̃ (Fritsch–Butland slopes inside, the three-point PCHIP slope at ε = 0, the last
/// secant at the last point), so T̃ is C¹, increasing and passes through every point;
/// beyond the last point it continues with that last secant slope (a straight line).
///
/// Compression. A knit carries no compression (tension field, as the isotropic law):
/// the curve is evaluated at a smoothed ramp s(ε) of the strain,
///   T(ε) = T̃(s(ε)),  s = 0 (ε ≤ −δ),  s = ε (ε ≥ δ),  C² in between,
/// with δ the smoothing width (engineering strain). T is C¹ and the strip energy
///   w(ε) = ∫_{−δ}^{ε} T(s) ds   (J/m², per unit rest area of the strip)
/// is C²; for ε ≥ δ the tension is exactly the measured curve.
#include <vector>

namespace tightfit {

/// The C² ramp s(ε) ≈ max(ε, 0) of width δ and its first three derivatives:
/// s = 0 for ε ≤ −δ, ε for ε ≥ δ, and δ/4 (3t²/2 − t⁴/4 + 2t + 3/4), t = ε/δ, between.
struct SmoothRamp {
  double value = 0.0, d1 = 0.0, d2 = 0.0, d3 = 0.0;
};
SmoothRamp smooth_ramp(double strain, double width);

class FabricCurve {
 public:
  /// `strain` (engineering, ≥ 0, strictly increasing) and `tension_n_per_m` (≥ 0,
  /// strictly increasing), of equal length ≥ 2. A curve that does not start at strain 0
  /// starts at (0, 0); one that starts at strain 0 must start at tension 0. `smoothing`
  /// δ > 0 is the width of the compression ramp, kept below half the first point's
  /// strain. Throws std::invalid_argument naming the array and the point that is wrong.
  FabricCurve(std::vector<double> strain, std::vector<double> tension_n_per_m,
              double smoothing = 1e-3);

  /// Strip energy w (J/m²), tension T = dw/dε (N/m) and stiffness dT/dε (N/m) at `strain`.
  struct Evaluation {
    double energy = 0.0, tension = 0.0, stiffness = 0.0;
  };
  /// `order` 0: energy only; 1: and tension; 2: all three.
  Evaluation evaluate(double strain, int order = 2) const;
  double tension(double strain) const { return evaluate(strain, 1).tension; }

  /// The interpolation points, (0, 0) first (N/m against strain).
  const std::vector<double>& strains() const { return strain_; }
  const std::vector<double>& tensions() const { return tension_; }
  /// Secant stiffness of the first segment, T(ε₁)/ε₁ (N/m).
  double initial_stiffness() const { return tension_[1] / strain_[1]; }
  /// Slope of the straight continuation beyond the last point (N/m).
  double final_stiffness() const { return slope_.back(); }
  double smoothing() const { return delta_; }

 private:
  /// T̃, dT̃/dε and ∫_0^ε T̃ for ε ≥ 0 (the unsmoothed interpolant).
  Evaluation interpolant(double strain, int order) const;

  std::vector<double> strain_;
  std::vector<double> tension_;
  std::vector<double> slope_;       // Hermite slope at each point
  std::vector<double> cumulative_;  // ∫_0^{ε_k} T̃ at each point
  double delta_ = 1e-3;
  double band_energy_ = 0.0;  // w(δ)
};

}  // namespace tightfit
