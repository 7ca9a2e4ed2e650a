#include "tightfit/physics/fabric_law.hpp"

#include <cmath>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

/// One direction of the measured law: ε = √c − 1 with dε/dc and d²ε/dc², the curve's
/// strip energy, tension and stiffness at ε, and the compression ramp s(ε).
struct Direction {
  bool active = false;  // ε > −δ: tension, ramp or coupling can be non-zero
  double de = 0.0, d2e = 0.0;
  FabricCurve::Evaluation curve;
  SmoothRamp ramp;
};

Direction direction(const FabricCurve& curve, double c, int order) {
  Direction d;
  if (!(c > 0.0)) return d;
  const double lambda = std::sqrt(c);
  const double strain = lambda - 1.0;
  if (strain <= -curve.smoothing()) return d;
  d.active = true;
  d.de = 0.5 / lambda;
  d.d2e = -0.25 / (lambda * c);
  d.curve = curve.evaluate(strain, order);
  d.ramp = smooth_ramp(strain, curve.smoothing());
  return d;
}

}  // namespace

FabricLaw::FabricLaw(const ClothMaterial& material) : material_(material), isotropic_(material) {
  if (const MeasuredFabric* m = material.measured.get()) {
    if (!(m->coupling >= 0.0 && m->coupling < 1.0))
      throw InputError("fabric " + m->name, "coupling must lie in [0, 1)");
    if (!(m->shear_n_per_m > 0.0) || !std::isfinite(m->shear_n_per_m))
      throw InputError("fabric " + m->name, "shear stiffness must be > 0");
    coupling_ = m->coupling * std::sqrt(m->worn_course().initial_stiffness() *
                                        m->worn_wale().initial_stiffness());
  }
}

FabricLaw::Derivatives FabricLaw::evaluate(const Vec3& c, int order) const {
  Derivatives out;
  if (!measured()) {
    const RelaxedStVK::Derivatives d =
        isotropic_.evaluate(c[0] + c[1], c[0] * c[1] - c[2] * c[2], order);
    out.value = d.value;
    if (order < 1) return out;
    const Vec3 di1(1.0, 1.0, 0.0);
    const Vec3 di2(c[1], c[0], -2.0 * c[2]);
    out.gradient = d.gradient[0] * di1 + d.gradient[1] * di2;
    if (order < 2) return out;
    Eigen::Matrix<double, 2, 3> j;
    j.row(0) = di1.transpose();
    j.row(1) = di2.transpose();
    Mat3 hi2 = Mat3::Zero();
    hi2(0, 1) = hi2(1, 0) = 1.0;
    hi2(2, 2) = -2.0;
    out.hessian = j.transpose() * d.hessian * j + d.gradient[1] * hi2;
    return out;
  }
  const MeasuredFabric& m = *material_.measured;
  const double inv_t = 1.0 / material_.thickness;
  const double shear = m.shear_n_per_m;
  const Direction x = direction(m.worn_course(), c[0], order);
  const Direction y = direction(m.worn_wale(), c[1], order);
  // Shear acts unless both directions are slack: G C_xy²/2 times g = h_x + h_y − h_x h_y,
  // h = s'(ε) (1 stretched, 0 slack).
  const double hx = x.ramp.d1, hy = y.ramp.d1;
  const double g = hx + hy - hx * hy;
  const double q = 0.5 * shear * c[2] * c[2];
  out.value =
      inv_t * (x.curve.energy + y.curve.energy + coupling_ * x.ramp.value * y.ramp.value + q * g);
  if (order < 1) return out;
  const double fx =
      x.curve.tension + coupling_ * x.ramp.d1 * y.ramp.value + q * x.ramp.d2 * (1.0 - hy);
  const double fy =
      y.curve.tension + coupling_ * y.ramp.d1 * x.ramp.value + q * y.ramp.d2 * (1.0 - hx);
  out.gradient = inv_t * Vec3(fx * x.de, fy * y.de, shear * c[2] * g);
  if (order < 2) return out;
  const double fxx =
      x.curve.stiffness + coupling_ * x.ramp.d2 * y.ramp.value + q * x.ramp.d3 * (1.0 - hy);
  const double fyy =
      y.curve.stiffness + coupling_ * y.ramp.d2 * x.ramp.value + q * y.ramp.d3 * (1.0 - hx);
  const double fxy = coupling_ * x.ramp.d1 * y.ramp.d1 - q * x.ramp.d2 * y.ramp.d2;
  out.hessian.setZero();
  out.hessian(0, 0) = inv_t * (fxx * x.de * x.de + fx * x.d2e);
  out.hessian(1, 1) = inv_t * (fyy * y.de * y.de + fy * y.d2e);
  out.hessian(0, 1) = out.hessian(1, 0) = inv_t * fxy * x.de * y.de;
  out.hessian(0, 2) = out.hessian(2, 0) = inv_t * shear * c[2] * x.ramp.d2 * (1.0 - hy) * x.de;
  out.hessian(1, 2) = out.hessian(2, 1) = inv_t * shear * c[2] * y.ramp.d2 * (1.0 - hx) * y.de;
  out.hessian(2, 2) = inv_t * shear * g;
  return out;
}

double FabricLaw::reference_stiffness() const {
  if (!measured()) return material_.youngs_modulus * material_.thickness;
  auto secant = [](const FabricCurve& c) { return c.tensions().back() / c.strains().back(); };
  const MeasuredFabric& m = *material_.measured;
  return std::sqrt(secant(m.worn_course()) * secant(m.worn_wale()));
}

Mat2 FabricLaw::second_piola(const Mat2& C) const {
  if (!measured()) return isotropic_.second_piola(C);
  const Vec3 g = evaluate(strain_components(C), 1).gradient;
  Mat2 s;
  s << 2.0 * g[0], g[2], g[2], 2.0 * g[1];
  return s;
}

ClothRegime FabricLaw::regime(const Mat2& C) const {
  if (!measured()) return isotropic_.regime(C);
  const int stretched = (C(0, 0) > 1.0 ? 1 : 0) + (C(1, 1) > 1.0 ? 1 : 0);
  return stretched == 2 ? ClothRegime::kTaut
                        : (stretched == 1 ? ClothRegime::kWrinkled : ClothRegime::kSlack);
}

}  // namespace tightfit
