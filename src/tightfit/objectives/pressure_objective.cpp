#include "tightfit/objectives/pressure_objective.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "tightfit/common/error.hpp"
#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/geometry/surface_topology.hpp"
#include "tightfit/objectives/autodiff.hpp"

namespace tightfit {
namespace {

using namespace autodiff;  // NOLINT: the AD helper types

const std::string kPressureSource = "pressure objective";

/// Mid-edge operator pieces of one face: Λ = Σ_i (θ_i/2 + s_i φ_i) B_i.
template <typename S>
struct FaceOperator {
  S area;
  std::array<Mat3T<S>, 3> b;  // (l_i/A) t_i t_iᵀ
  std::array<S, 3> theta;     // signed dihedral angle of edge i (0 on the boundary)
};

/// `p`: the face's corners 0..2, then the vertices across edges 0..2 (ignored where
/// `has_opposite[i]` is false). Throws SolverError for a degenerate face.
template <typename S>
FaceOperator<S> face_operator(const std::array<Vec3T<S>, 6>& p,
                              const std::array<bool, 3>& has_opposite, int face) {
  using std::atan2;
  using std::sqrt;
  FaceOperator<S> op;
  const Vec3T<S> n = (p[1] - p[0]).cross(p[2] - p[0]);
  const S twice = sqrt(n.squaredNorm());
  const double scale =
      value_of((p[1] - p[0]).squaredNorm()) + value_of((p[2] - p[0]).squaredNorm());
  if (!(value_of(twice) > 1e-12 * scale))
    throw SolverError("pressure objective: garment face " + std::to_string(face) +
                      " is degenerate");
  const Vec3T<S> nh = n / twice;
  op.area = 0.5 * twice;
  for (int i = 0; i < 3; ++i) {
    const Vec3T<S> e = p[(i + 1) % 3] - p[i];
    const S len = sqrt(e.squaredNorm());
    const Vec3T<S> dir = e / len;
    const Vec3T<S> out = dir.cross(nh);
    op.b[i] = (len / op.area) * out * out.transpose();
    op.theta[i] = S(0.0);
    if (!has_opposite[i]) continue;
    const Vec3T<S> ng = (p[i] - p[(i + 1) % 3]).cross(p[3 + i] - p[(i + 1) % 3]);
    const S ng_len = sqrt(ng.squaredNorm());
    if (!(value_of(ng_len) > 0.0))
      throw SolverError("pressure objective: the face across edge " + std::to_string(i) +
                        " of garment face " + std::to_string(face) + " is degenerate");
    const Vec3T<S> ngh = ng / ng_len;
    op.theta[i] = atan2(nh.cross(ngh).dot(dir), nh.dot(ngh));
  }
  return op;
}

/// ⟨B_i, B_j⟩ (Frobenius) of a face, 3×3.
template <typename S>
Eigen::Matrix<S, 3, 3> gram(const FaceOperator<S>& op) {
  Eigen::Matrix<S, 3, 3> g;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g(i, j) = op.b[i].cwiseProduct(op.b[j]).sum();
  return g;
}

/// Young-Laplace pressure t tr(σ Λ) of a cloth element with deformed corners x, rest
/// corners r, and shape operator lambda.
template <typename S>
S element_pressure(const RelaxedStVK& law, const std::array<Vec3T<S>, 3>& x,
                   const std::array<Vec2T<S>, 3>& r, const Mat3T<S>& lambda, int face) {
  using std::sqrt;
  Mat2T<S> dm;
  Mat32T<S> ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = r[k + 1] - r[0];
    ds.col(k) = x[k + 1] - x[0];
  }
  const Mat32T<S> f = ds * inverse2(dm);
  const Mat2T<S> c = f.transpose() * f;
  const S det_c = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  if (!(value_of(det_c) > 1e-24))
    throw SolverError("pressure objective: garment face " + std::to_string(face) +
                      " is degenerate (zero deformed area)");
  const S j = sqrt(det_c);
  const Mat3T<S> sigma = f * second_piola(law, c) * f.transpose() / j;
  return law.material().thickness * sigma.cwiseProduct(lambda).sum();
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
  const SurfaceTopology topo(garment_triangles_, num_garment_);
  if (!topo.non_manifold_edges().empty())
    throw InputError(kPressureSource, "garment mesh has edges with more than two faces");
  if (!topo.inconsistently_oriented_edges().empty())
    throw InputError(kPressureSource, "garment mesh faces are not consistently oriented");
  num_edges_ = topo.num_edges();
  face_edge_.resize(m);
  face_sign_.resize(m);
  face_opposite_.resize(m);
  for (int f = 0; f < static_cast<int>(m); ++f)
    for (int i = 0; i < 3; ++i) {
      const int edge = topo.face_edge(f, i);
      face_edge_[f][i] = edge;
      face_sign_[f][i] = topo.edge_faces(edge)[0] == f ? 1 : -1;
      const SurfaceTopology::Across a = topo.across(f, i);
      face_opposite_[f][i] = a.face < 0 ? -1 : garment_triangles_(a.face, (a.edge_in_face + 2) % 3);
    }
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

/// Corner and across-edge positions of face f as plain doubles.
std::array<Vec3, 6> face_points(const VecX& x, const Triangles& tri,
                                const std::array<int, 3>& opposite, int f) {
  std::array<Vec3, 6> p;
  for (int k = 0; k < 3; ++k) {
    p[k] = x.segment<3>(3 * tri(f, k));
    p[3 + k] = opposite[k] >= 0 ? Vec3(x.segment<3>(3 * opposite[k])) : Vec3::Zero();
  }
  return p;
}

std::array<bool, 3> has_opposite(const std::array<int, 3>& opposite) {
  return {opposite[0] >= 0, opposite[1] >= 0, opposite[2] >= 0};
}

}  // namespace

namespace {

/// The mid-edge system at x: every face's operator pieces, the factorized matrix K of
/// the edge unknowns and their solution φ.
struct EdgeSystem {
  std::vector<FaceOperator<double>> ops;
  std::unique_ptr<SparseCholesky> solver = std::make_unique<SparseCholesky>();
  VecX phi;
};

EdgeSystem solve_edge_system(const VecX& x, const Triangles& tri,
                             const std::vector<std::array<int, 3>>& face_edge,
                             const std::vector<std::array<int, 3>>& face_sign,
                             const std::vector<std::array<int, 3>>& face_opposite, int num_edges) {
  const int m = static_cast<int>(tri.rows());
  EdgeSystem sys;
  sys.ops.reserve(m);
  std::vector<Triplet> trip;
  trip.reserve(9 * static_cast<std::size_t>(m));
  VecX rhs = VecX::Zero(num_edges);
  for (int f = 0; f < m; ++f) {
    sys.ops.push_back(face_operator<double>(face_points(x, tri, face_opposite[f], f),
                                            has_opposite(face_opposite[f]), f));
    const FaceOperator<double>& op = sys.ops.back();
    const Mat3 g = gram(op);
    for (int i = 0; i < 3; ++i) {
      double r = 0.0;
      for (int j = 0; j < 3; ++j) {
        trip.emplace_back(face_edge[f][i], face_edge[f][j],
                          op.area * face_sign[f][i] * face_sign[f][j] * g(i, j));
        r += 0.5 * op.theta[j] * g(i, j);
      }
      rhs[face_edge[f][i]] -= op.area * face_sign[f][i] * r;
    }
  }
  SparseMatrix k(num_edges, num_edges);
  k.setFromTriplets(trip.begin(), trip.end());
  if (!sys.solver->factorize(k))
    throw SolverError("pressure objective: mid-edge system is not positive definite");
  sys.phi = sys.solver->solve(rhs);
  return sys;
}

/// Λ_f of every face from a solved system.
std::vector<Mat3> operators_of(const EdgeSystem& sys,
                               const std::vector<std::array<int, 3>>& face_edge,
                               const std::vector<std::array<int, 3>>& face_sign) {
  std::vector<Mat3> out(sys.ops.size());
  for (std::size_t f = 0; f < sys.ops.size(); ++f) {
    out[f].setZero();
    for (int i = 0; i < 3; ++i)
      out[f] += (0.5 * sys.ops[f].theta[i] + face_sign[f][i] * sys.phi[face_edge[f][i]]) *
                sys.ops[f].b[i];
  }
  return out;
}

}  // namespace

std::vector<Mat3> PressureObjective::shape_operators(const VecX& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_garment_))
    throw std::invalid_argument("pressure objective: wrong position vector size");
  const EdgeSystem sys =
      solve_edge_system(x, garment_triangles_, face_edge_, face_sign_, face_opposite_, num_edges_);
  return operators_of(sys, face_edge_, face_sign_);
}

namespace {

/// p_e of every element given its shape operator.
VecX element_pressures(const RelaxedStVK& law, const DesignState& state,
                       const Triangles& garment_tri, const Triangles& pattern_tri,
                       const std::vector<Mat3>& lambda) {
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
  const EdgeSystem sys = solve_edge_system(state.x, garment_triangles_, face_edge_, face_sign_,
                                           face_opposite_, num_edges_);
  const VecX& phi = sys.phi;
  const VecX p = element_pressures(law_, state, garment_triangles_, pattern_triangles_,
                                   operators_of(sys, face_edge_, face_sign_));
  const int m = static_cast<int>(garment_triangles_.rows());

  // Pass 1: ∂T/∂x, ∂T/∂Xbar at fixed φ, and ∂T/∂φ. Local variables: 18 positions (corners,
  // then the vertices across edges 0..2), 6 rest coordinates, 3 edge unknowns.
  constexpr int kN = 27;
  using S = Scalar<kN>;
  VecX d_phi = VecX::Zero(num_edges_);
  bool any = false;
  for (int f = 0; f < m; ++f) {
    if (inside_all(p[f], min_pressure_[f], max_pressure_[f], regions_, f)) continue;  // zero slope
    any = true;
    const std::array<Vec3, 6> pd = face_points(state.x, garment_triangles_, face_opposite_[f], f);
    std::array<Vec3T<S>, 6> pa;
    for (int v = 0; v < 6; ++v)
      for (int c = 0; c < 3; ++c) pa[v](c) = variable<kN>(pd[v](c), 3 * v + c);
    std::array<Vec2T<S>, 3> ra;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c)
        ra[k](c) = variable<kN>(state.rest(pattern_triangles_(f, k), c), 18 + 2 * k + c);
    const FaceOperator<S> op = face_operator<S>(pa, has_opposite(face_opposite_[f]), f);
    Mat3T<S> lambda = Mat3T<S>::Zero();
    for (int i = 0; i < 3; ++i) {
      const S phi_i = variable<kN>(phi[face_edge_[f][i]], 24 + i);
      lambda += (0.5 * op.theta[i] + double(face_sign_[f][i]) * phi_i) * op.b[i];
    }
    const std::array<Vec3T<S>, 3> xa = {pa[0], pa[1], pa[2]};
    const S pressure = element_pressure<S>(law_, xa, ra, lambda, f);
    const S t = rest_area<S>(ra) *
                element_penalty<S>(pressure, min_pressure_[f], max_pressure_[f], regions_, f, xa);
    const Eigen::Matrix<double, kN, 1>& g = t.derivatives();
    for (int k = 0; k < 3; ++k) {
      d_x.segment<3>(3 * garment_triangles_(f, k)) += g.segment<3>(3 * k);
      if (face_opposite_[f][k] >= 0)
        d_x.segment<3>(3 * face_opposite_[f][k]) += g.segment<3>(9 + 3 * k);
      d_rest.segment<2>(2 * pattern_triangles_(f, k)) += g.segment<2>(18 + 2 * k);
      d_phi[face_edge_[f][k]] += g[24 + k];
    }
  }
  if (!any) return;

  // Adjoint of the φ system: K μ = ∂T/∂φ, then subtract ∂/∂x Σ_f A_f tr(Λ_f Γ_f).
  const VecX mu = sys.solver->solve(d_phi);

  constexpr int kM = 18;
  using R = Scalar<kM>;
  for (int f = 0; f < m; ++f) {
    const std::array<Vec3, 6> pd = face_points(state.x, garment_triangles_, face_opposite_[f], f);
    std::array<Vec3T<R>, 6> pa;
    for (int v = 0; v < 6; ++v)
      for (int c = 0; c < 3; ++c) pa[v](c) = variable<kM>(pd[v](c), 3 * v + c);
    const FaceOperator<R> op = face_operator<R>(pa, has_opposite(face_opposite_[f]), f);
    const Eigen::Matrix<R, 3, 3> gm = gram(op);
    R h(0.0);
    for (int i = 0; i < 3; ++i) {
      const R coeff_i = 0.5 * op.theta[i] + face_sign_[f][i] * phi[face_edge_[f][i]];
      for (int j = 0; j < 3; ++j)
        h += coeff_i * (face_sign_[f][j] * mu[face_edge_[f][j]]) * gm(i, j);
    }
    h *= op.area;
    const Eigen::Matrix<double, kM, 1>& g = h.derivatives();
    for (int k = 0; k < 3; ++k) {
      d_x.segment<3>(3 * garment_triangles_(f, k)) -= g.segment<3>(3 * k);
      if (face_opposite_[f][k] >= 0)
        d_x.segment<3>(3 * face_opposite_[f][k]) -= g.segment<3>(9 + 3 * k);
    }
  }
}

}  // namespace tightfit
