#include "tightfit/objectives/pressure_objective.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/autodiff.hpp"
#include "tightfit/physics/element_pressure.hpp"
#include "tightfit/physics/mid_edge_kernel.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"

namespace tightfit {
namespace {

using namespace autodiff;  // NOLINT: the AD helper types

const std::string kPressureSource = "pressure objective";

/// Deformation gradient F = Ds Dm⁻¹ (3×2) of a cloth element with deformed corners x and
/// rest corners r.
template <typename S>
Mat32T<S> deformation_gradient(const std::array<Vec3T<S>, 3>& x, const std::array<Vec2T<S>, 3>& r) {
  Mat2T<S> dm;
  Mat32T<S> ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = r[k + 1] - r[0];
    ds.col(k) = x[k + 1] - x[0];
  }
  return ds * inverse2(dm);
}

/// Young-Laplace pressure t tr(σ Λ) of a cloth element with deformed corners x, rest
/// corners r, and shape operator lambda (physics/element_pressure.hpp).
template <typename S>
S element_pressure(const FabricLaw& law, const std::array<Vec3T<S>, 3>& x,
                   const std::array<Vec2T<S>, 3>& r, const Mat3T<S>& lambda, int face) {
  const std::optional<S> p =
      tightfit::element_pressure<S>(law, deformation_gradient<S>(x, r), lambda);
  if (!p)
    throw SolverError("pressure objective: garment face " + std::to_string(face) +
                      " is degenerate (zero deformed area)");
  return *p;
}

/// Rest area |det Dm|/2 of an element.
template <typename S>
S rest_area(const std::array<Vec2T<S>, 3>& r) {
  const Vec2T<S> e1 = r[1] - r[0], e2 = r[2] - r[0];
  const S det = e1(0) * e2(1) - e1(1) * e2(0);
  return value_of(det) >= 0.0 ? S(0.5 * det) : S(-0.5 * det);
}

template <typename S>
S penalty(const S& p, double lo, double hi) {
  if (value_of(p) < lo) return (p - lo) * (p - lo);
  if (value_of(p) > hi) return (p - hi) * (p - hi);
  return S(0.0);
}

/// A_e Σ pen of one element: its own range plus every candidate region's weighted range.
template <typename S>
S element_penalty(const S& pressure, double lo, double hi, const PressureRegions& regions, int e,
                  const std::array<Vec3T<S>, 3>& corners) {
  S total = penalty<S>(pressure, lo, hi);
  for (int r : regions.candidates(e)) {
    const PressureRegion& region = regions[r];
    if (value_of(pressure) >= region.min_pa && value_of(pressure) <= region.max_pa) continue;
    total +=
        regions.band_weight<S>(r, corners) * penalty<S>(pressure, region.min_pa, region.max_pa);
  }
  return total;
}

/// Whether element e's penalty and its slope vanish (inside every range that applies).
bool inside_all(double pressure, double lo, double hi, const PressureRegions& regions, int e) {
  if (pressure < lo || pressure > hi) return false;
  for (int r : regions.candidates(e))
    if (pressure < regions[r].min_pa || pressure > regions[r].max_pa) return false;
  return true;
}

}  // namespace

PressureObjective::PressureObjective(const Garment& garment, const ClothMaterial& material,
                                     PressureRegions regions)
    : PressureObjective(garment, material,
                        VecX::Constant(garment.topology->garment_triangles.rows(),
                                       -std::numeric_limits<double>::infinity()),
                        VecX::Constant(garment.topology->garment_triangles.rows(),
                                       std::numeric_limits<double>::infinity())) {
  regions_ = std::move(regions);
}

PressureObjective::PressureObjective(const Garment& garment, const ClothMaterial& material,
                                     double min_pressure, double max_pressure)
    : PressureObjective(garment, material,
                        VecX::Constant(garment.topology->garment_triangles.rows(), min_pressure),
                        VecX::Constant(garment.topology->garment_triangles.rows(), max_pressure)) {}

PressureObjective::PressureObjective(const Garment& garment, const ClothMaterial& material,
                                     VecX min_pressure, VecX max_pressure)
    : pattern_triangles_(garment.topology->pattern_triangles),
      garment_triangles_(garment.topology->garment_triangles),
      num_garment_(garment.num_garment_vertices()),
      num_pattern_(garment.num_pattern_vertices()),
      law_(material),
      min_pressure_(std::move(min_pressure)),
      max_pressure_(std::move(max_pressure)),
      regions_(garment, {}, kPressureSource) {
  const Eigen::Index m = garment_triangles_.rows();
  if (pattern_triangles_.rows() != m)
    throw InputError(kPressureSource, "garment and pattern triangle counts differ");
  if (min_pressure_.size() != m || max_pressure_.size() != m)
    throw InputError(kPressureSource, "pressure range has " + std::to_string(min_pressure_.size()) +
                                          "/" + std::to_string(max_pressure_.size()) +
                                          " entries for " + std::to_string(m) + " triangles");
  const double inf = std::numeric_limits<double>::infinity();
  for (Eigen::Index e = 0; e < m; ++e) {
    const bool no_range = min_pressure_[e] == -inf && max_pressure_[e] == inf;
    if (!no_range && (!std::isfinite(min_pressure_[e]) || !std::isfinite(max_pressure_[e]) ||
                      min_pressure_[e] > max_pressure_[e]))
      throw InputError(kPressureSource, "pressure range of triangle " + std::to_string(e) +
                                            " must be finite with min <= max");
  }
  for (Eigen::Index e = 0; e < m; ++e)
    for (int k = 0; k < 3; ++k)
      if (garment_triangles_(e, k) < 0 || garment_triangles_(e, k) >= num_garment_ ||
          pattern_triangles_(e, k) < 0 || pattern_triangles_(e, k) >= num_pattern_)
        throw InputError(kPressureSource,
                         "triangle " + std::to_string(e) + " has an index out of range");
  topology_ =
      std::make_shared<const MidEdgeTopology>(garment_triangles_, num_garment_, kPressureSource);
}

void PressureObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument("pressure objective: state has " + std::to_string(state.x.size()) +
                                " position entries and " + std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

namespace {

/// Corner and across-edge positions of face f as plain doubles (zero where no face is
/// across).
std::array<Vec3, 6> face_points(const VecX& x, const Triangles& tri,
                                const std::array<int, 3>& across, int f) {
  std::array<Vec3, 6> p;
  for (int k = 0; k < 3; ++k) {
    p[k] = x.segment<3>(3 * tri(f, k));
    p[3 + k] = across[k] >= 0 ? Vec3(x.segment<3>(3 * across[k])) : Vec3::Zero();
  }
  return p;
}

std::array<bool, 3> has_across(const std::array<int, 3>& across) {
  return {across[0] >= 0, across[1] >= 0, across[2] >= 0};
}

Eigen::Map<const Points3> as_points(const VecX& x) { return {x.data(), x.size() / 3, 3}; }

/// p_e of every element given its shape operator.
VecX element_pressures(const FabricLaw& law, const DesignState& state, const Triangles& garment_tri,
                       const Triangles& pattern_tri, const std::vector<Mat3>& lambda) {
  VecX p(garment_tri.rows());
  for (int f = 0; f < static_cast<int>(garment_tri.rows()); ++f) {
    std::array<Vec3, 3> x;
    std::array<Vec2, 3> r;
    for (int k = 0; k < 3; ++k) {
      x[k] = state.x.segment<3>(3 * garment_tri(f, k));
      r[k] = state.rest.row(pattern_tri(f, k)).transpose();
    }
    p[f] = element_pressure<double>(law, x, r, lambda[f], f);
  }
  return p;
}

}  // namespace

std::vector<Mat3> PressureObjective::shape_operators(const VecX& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_garment_))
    throw std::invalid_argument("pressure objective: wrong position vector size");
  MidEdgeShapeOperator op(topology_);
  return op.compute(as_points(x));
}

VecX PressureObjective::pressures(const DesignState& state) const {
  check(state);
  return element_pressures(law_, state, garment_triangles_, pattern_triangles_,
                           shape_operators(state.x));
}

double PressureObjective::value(const DesignState& state) const {
  const VecX p = pressures(state);
  double total = 0.0;
  for (int f = 0; f < static_cast<int>(p.size()); ++f) {
    std::array<Vec2, 3> r;
    std::array<Vec3, 3> x;
    for (int k = 0; k < 3; ++k) {
      r[k] = state.rest.row(pattern_triangles_(f, k)).transpose();
      x[k] = state.x.segment<3>(3 * garment_triangles_(f, k));
    }
    total += rest_area<double>(r) *
             element_penalty<double>(p[f], min_pressure_[f], max_pressure_[f], regions_, f, x);
  }
  return total;
}

void PressureObjective::add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const {
  check(state);
  if (d_x.size() != state.x.size() || d_rest.size() != 2 * state.rest.rows())
    throw std::invalid_argument("pressure objective: gradient vectors have the wrong size");
  const MidEdgeTopology& topo = *topology_;
  MidEdgeShapeOperator mid_edge(topology_);
  const VecX p = element_pressures(law_, state, garment_triangles_, pattern_triangles_,
                                   mid_edge.compute(as_points(state.x)));
  const VecX& phi = mid_edge.edge_variables();
  const int m = static_cast<int>(garment_triangles_.rows());

  // Pass 1: ∂T/∂x, ∂T/∂Xbar at fixed φ, and ∂T/∂φ. Local variables: 18 positions (corners,
  // then the vertices across edges 0..2), 6 rest coordinates, 3 edge unknowns.
  constexpr int kN = 27;
  using S = Scalar<kN>;
  VecX d_phi = VecX::Zero(topo.num_edges());
  bool any = false;
  for (int f = 0; f < m; ++f) {
    if (inside_all(p[f], min_pressure_[f], max_pressure_[f], regions_, f)) continue;  // zero slope
    any = true;
    const std::array<int, 3> across = topo.across_vertices(f);
    const std::array<int, 3> edges = topo.edges(f);
    const std::array<Vec3, 6> pd = face_points(state.x, garment_triangles_, across, f);
    std::array<Vec3T<S>, 6> pa;
    for (int v = 0; v < 6; ++v)
      for (int c = 0; c < 3; ++c) pa[v](c) = variable<kN>(pd[v](c), 3 * v + c);
    std::array<Vec2T<S>, 3> ra;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c)
        ra[k](c) = variable<kN>(state.rest(pattern_triangles_(f, k), c), 18 + 2 * k + c);
    const mid_edge::FaceOperator<S> op = mid_edge::face_operator<S>(pa, has_across(across), f);
    std::array<S, 3> phi_f;
    for (int i = 0; i < 3; ++i) phi_f[i] = variable<kN>(phi[edges[i]], 24 + i);
    const Mat3T<S> lambda = mid_edge::shape_operator<S, S>(op, topo.signs(f), phi_f);
    const std::array<Vec3T<S>, 3> xa = {pa[0], pa[1], pa[2]};
    const S pressure = element_pressure<S>(law_, xa, ra, lambda, f);
    const S t = rest_area<S>(ra) *
                element_penalty<S>(pressure, min_pressure_[f], max_pressure_[f], regions_, f, xa);
    const Eigen::Matrix<double, kN, 1>& g = t.derivatives();
    for (int k = 0; k < 3; ++k) {
      d_x.segment<3>(3 * garment_triangles_(f, k)) += g.segment<3>(3 * k);
      if (across[k] >= 0) d_x.segment<3>(3 * across[k]) += g.segment<3>(9 + 3 * k);
      d_rest.segment<2>(2 * pattern_triangles_(f, k)) += g.segment<2>(18 + 2 * k);
      d_phi[edges[k]] += g[24 + k];
    }
  }
  if (!any) return;

  // Adjoint of the φ system: K μ = ∂T/∂φ, then subtract ∂/∂x Σ_f A_f tr(Λ_f Γ_f).
  const VecX mu = mid_edge.solve_with_system_matrix(d_phi);

  constexpr int kM = 18;
  using R = Scalar<kM>;
  for (int f = 0; f < m; ++f) {
    const std::array<int, 3> across = topo.across_vertices(f);
    const std::array<int, 3> edges = topo.edges(f);
    const std::array<int, 3> signs = topo.signs(f);
    const std::array<Vec3, 6> pd = face_points(state.x, garment_triangles_, across, f);
    std::array<Vec3T<R>, 6> pa;
    for (int v = 0; v < 6; ++v)
      for (int c = 0; c < 3; ++c) pa[v](c) = variable<kM>(pd[v](c), 3 * v + c);
    const mid_edge::FaceOperator<R> op = mid_edge::face_operator<R>(pa, has_across(across), f);
    const Mat3T<R> gm = mid_edge::gram(op);
    R h(0.0);
    for (int i = 0; i < 3; ++i) {
      const R coeff_i = mid_edge::coefficient(op, i, signs[i], phi[edges[i]]);
      for (int j = 0; j < 3; ++j) h += coeff_i * (signs[j] * mu[edges[j]]) * gm(i, j);
    }
    h *= op.area;
    const Eigen::Matrix<double, kM, 1>& g = h.derivatives();
    for (int k = 0; k < 3; ++k) {
      d_x.segment<3>(3 * garment_triangles_(f, k)) -= g.segment<3>(3 * k);
      if (across[k] >= 0) d_x.segment<3>(3 * across[k]) -= g.segment<3>(9 + 3 * k);
    }
  }
}

}  // namespace tightfit
