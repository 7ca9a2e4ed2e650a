#include "tightfit/objectives/stretch_objective.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/objectives/element_kinematics.hpp"

namespace tightfit {
namespace {

ElementKinematics stretch_kinematics(const DesignState& s, const Triangles& tri,
                                     const std::vector<int>& to_garment, Eigen::Index e) {
  return element_kinematics(s, tri, to_garment, e, "stretch objective");
}

/// Eigenvalues λ1 >= λ2 of a symmetric 2×2 matrix, with m = mean and r = half gap.
struct Eigen2 {
  double m = 0.0;
  double r = 0.0;
  double l1() const { return m + r; }
  double l2() const { return m - r; }
};

Eigen2 eigen2(const Mat2& c) {
  const double half = 0.5 * (c(0, 0) - c(1, 1));
  const double off = 0.5 * (c(0, 1) + c(1, 0));
  return {0.5 * (c(0, 0) + c(1, 1)), std::hypot(half, off)};
}

}  // namespace

StretchObjective::StretchObjective(const Garment& garment, StretchBounds bounds)
    : triangles_(garment.topology->pattern_triangles),
      pattern_to_garment_(garment.topology->pattern_to_garment),
      num_garment_(garment.num_garment_vertices()),
      num_pattern_(garment.num_pattern_vertices()) {
  if (!(bounds.min_stretch > 0.0) || !(bounds.max_stretch >= bounds.min_stretch) ||
      !std::isfinite(bounds.min_stretch))
    throw InputError("stretch objective", "stretch bounds must satisfy 0 < min <= max (got " +
                                              std::to_string(bounds.min_stretch) + ", " +
                                              std::to_string(bounds.max_stretch) + ")");
  lambda_min_ = bounds.min_stretch * bounds.min_stretch;
  lambda_max_ = bounds.max_stretch * bounds.max_stretch;  // +inf stays +inf
}

void StretchObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument("stretch objective: state has " + std::to_string(state.x.size()) +
                                " position entries and " + std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

std::vector<Vec2> StretchObjective::cauchy_green_eigenvalues(const DesignState& state) const {
  check(state);
  std::vector<Vec2> out(triangles_.rows());
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const Eigen2 ev = eigen2(stretch_kinematics(state, triangles_, pattern_to_garment_, e).c);
    out[e] = Vec2(ev.l1(), ev.l2());
  }
  return out;
}

double StretchObjective::value(const DesignState& state) const {
  check(state);
  auto pen = [&](double l) {
    if (l < lambda_min_) return (l - lambda_min_) * (l - lambda_min_);
    if (l > lambda_max_) return (l - lambda_max_) * (l - lambda_max_);
    return 0.0;
  };
  double total = 0.0;
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const ElementKinematics k = stretch_kinematics(state, triangles_, pattern_to_garment_, e);
    const Eigen2 ev = eigen2(k.c);
    total += k.area * (pen(ev.l1()) + pen(ev.l2()));
  }
  return total;
}

void StretchObjective::add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const {
  check(state);
  if (d_x.size() != state.x.size() || d_rest.size() != 2 * state.rest.rows())
    throw std::invalid_argument("stretch objective: gradient vectors have the wrong size");
  auto pen = [&](double l) {
    if (l < lambda_min_) return (l - lambda_min_) * (l - lambda_min_);
    if (l > lambda_max_) return (l - lambda_max_) * (l - lambda_max_);
    return 0.0;
  };
  auto dpen = [&](double l) {
    if (l < lambda_min_) return 2.0 * (l - lambda_min_);
    if (l > lambda_max_) return 2.0 * (l - lambda_max_);
    return 0.0;
  };
  auto ddpen = [&](double l) { return (l < lambda_min_ || l > lambda_max_) ? 2.0 : 0.0; };
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const ElementKinematics k = stretch_kinematics(state, triangles_, pattern_to_garment_, e);
    const Eigen2 ev = eigen2(k.c);
    const double l1 = ev.l1(), l2 = ev.l2();
    const double s = pen(l1) + pen(l2);
    if (s == 0.0 && dpen(l1) == 0.0 && dpen(l2) == 0.0) continue;
    const double gap = l1 - l2;
    const double divided =
        gap > 1e-12 * std::max(1.0, std::abs(ev.m)) ? (dpen(l1) - dpen(l2)) / gap : ddpen(ev.m);
    const Mat2 ds_dc =
        0.5 * (dpen(l1) + dpen(l2)) * Mat2::Identity() + divided * (k.c - ev.m * Mat2::Identity());
    // T_e = A s(C): ∂T_e/∂F = 2 A F ∂s/∂C.
    const Mat32 p = 2.0 * k.area * k.f * ds_dc;
    add_element_gradient(k, p, s, triangles_, pattern_to_garment_, e, d_x, d_rest);
  }
}

}  // namespace tightfit
