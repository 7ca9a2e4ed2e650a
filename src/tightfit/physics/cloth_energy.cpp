#include "tightfit/physics/cloth_energy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "tightfit/common/error.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/physics/assembly.hpp"
#include "tightfit/physics/autodiff.hpp"

namespace tightfit {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat3x9 = Eigen::Matrix<double, 3, 9>;

const std::string kClothSource = "cloth pattern";

/// Edge metric (E1·E1, E2·E2, E1·E2) of a triangle, E1 = p1 - p0, E2 = p2 - p0, with its
/// Jacobian with respect to (p0, p1, p2) (each Dim coordinates).
template <int Dim>
struct EdgeMetric {
  Vec3 value;
  Eigen::Matrix<double, 3, 3 * Dim> jacobian;
};

template <int Dim>
EdgeMetric<Dim> edge_metric(const Eigen::Matrix<double, Dim, 1>& p0,
                            const Eigen::Matrix<double, Dim, 1>& p1,
                            const Eigen::Matrix<double, Dim, 1>& p2) {
  const Eigen::Matrix<double, Dim, 1> e1 = p1 - p0;
  const Eigen::Matrix<double, Dim, 1> e2 = p2 - p0;
  EdgeMetric<Dim> m;
  m.value << e1.squaredNorm(), e2.squaredNorm(), e1.dot(e2);
  m.jacobian.setZero();
  m.jacobian.template block<1, Dim>(0, 0) = -2.0 * e1.transpose();
  m.jacobian.template block<1, Dim>(0, Dim) = 2.0 * e1.transpose();
  m.jacobian.template block<1, Dim>(1, 0) = -2.0 * e2.transpose();
  m.jacobian.template block<1, Dim>(1, 2 * Dim) = 2.0 * e2.transpose();
  m.jacobian.template block<1, Dim>(2, 0) = -(e1 + e2).transpose();
  m.jacobian.template block<1, Dim>(2, Dim) = e2.transpose();
  m.jacobian.template block<1, Dim>(2, 2 * Dim) = e1.transpose();
  return m;
}

/// Σ_k w_k ∇²(metric_k) with respect to (p0, p1, p2), which is (K ⊗ I_Dim) for the 3×3
/// vertex stencil K = 2w0 s1s1ᵀ + 2w1 s2s2ᵀ + w2 (s1s2ᵀ + s2s1ᵀ), s1 = (-1,1,0), s2 = (-1,0,1).
template <int Dim>
Eigen::Matrix<double, 3 * Dim, 3 * Dim> metric_curvature(const Vec3& w) {
  const Vec3 s1(-1.0, 1.0, 0.0);
  const Vec3 s2(-1.0, 0.0, 1.0);
  const Mat3 k = 2.0 * w[0] * s1 * s1.transpose() + 2.0 * w[1] * s2 * s2.transpose() +
                 w[2] * (s1 * s2.transpose() + s2 * s1.transpose());
  Eigen::Matrix<double, 3 * Dim, 3 * Dim> out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out.template block<Dim, Dim>(Dim * a, Dim * b) =
          k(a, b) * Eigen::Matrix<double, Dim, Dim>::Identity();
  return out;
}

/// Φ(v) = A f(I1, I2) per unit thickness, v = (G11, G22, G12, M11, M22, M12), with
/// D = det M, A = sqrt(D)/2, I1 = (G11 M22 + G22 M11 - 2 G12 M12)/D, I2 = det G / D.
struct Phi {
  double value = 0.0;
  Vec6 gradient = Vec6::Zero();
  Mat6 hessian = Mat6::Zero();
};

Phi element_phi(const Vec3& g, const Vec3& m, const RelaxedStVK& law, int order) {
  const double d = m[0] * m[1] - m[2] * m[2];
  const double sd = std::sqrt(d);
  const double area = 0.5 * sd;
  const double n1 = g[0] * m[1] + g[1] * m[0] - 2.0 * g[2] * m[2];
  const double n2 = g[0] * g[1] - g[2] * g[2];
  const double i1 = n1 / d;
  const double i2 = n2 / d;
  const RelaxedStVK::Derivatives f = law.evaluate(i1, i2, order);
  Phi phi;
  phi.value = area * f.value;
  if (order < 1) return phi;

  Vec6 dd, dn1, dn2;
  dd << 0, 0, 0, m[1], m[0], -2.0 * m[2];
  dn1 << m[1], m[0], -2.0 * m[2], g[1], g[0], -2.0 * g[2];
  dn2 << g[1], g[0], -2.0 * g[2], 0, 0, 0;
  const Vec6 di1 = dn1 / d - n1 * dd / (d * d);
  const Vec6 di2 = dn2 / d - n2 * dd / (d * d);
  const Vec6 da = dd / (4.0 * sd);
  const Vec6 df = f.gradient[0] * di1 + f.gradient[1] * di2;
  phi.gradient = f.value * da + area * df;
  if (order < 2) return phi;

  Mat6 hd = Mat6::Zero(), hn1 = Mat6::Zero(), hn2 = Mat6::Zero();
  hd(3, 4) = hd(4, 3) = 1.0;
  hd(5, 5) = -2.0;
  hn1(0, 4) = hn1(4, 0) = 1.0;
  hn1(1, 3) = hn1(3, 1) = 1.0;
  hn1(2, 5) = hn1(5, 2) = -2.0;
  hn2(0, 1) = hn2(1, 0) = 1.0;
  hn2(2, 2) = -2.0;
  const double d2 = d * d;
  const double d3 = d2 * d;
  auto quotient_hessian = [&](const Mat6& hn, const Vec6& dn, double n) -> Mat6 {
    return hn / d - (dn * dd.transpose() + dd * dn.transpose()) / d2 - n * hd / d2 +
           2.0 * n * dd * dd.transpose() / d3;
  };
  Eigen::Matrix<double, 2, 6> ji;
  ji.row(0) = di1.transpose();
  ji.row(1) = di2.transpose();
  const Mat6 hf = ji.transpose() * f.hessian * ji + f.gradient[0] * quotient_hessian(hn1, dn1, n1) +
                  f.gradient[1] * quotient_hessian(hn2, dn2, n2);
  const Mat6 ha = hd / (4.0 * sd) - dd * dd.transpose() / (8.0 * d * sd);
  phi.hessian = f.value * ha + da * df.transpose() + df * da.transpose() + area * hf;
  return phi;
}

}  // namespace

ClothEnergy::ClothEnergy(std::shared_ptr<const GarmentTopology> topology, const Points2& rest,
                         ClothMaterial material)
    : RestDependentEnergy(rest), topology_(std::move(topology)), law_(material) {
  if (!topology_) throw std::invalid_argument("ClothEnergy: null topology");
  check_rest(rest);
}

ClothEnergy::ClothEnergy(Triangles triangles, const Points2& rest,
                         std::vector<int> pattern_to_garment, int num_garment_vertices,
                         ClothMaterial material)
    : ClothEnergy(std::make_shared<const GarmentTopology>(
                      one_piece_topology(kClothSource, rest.rows(), std::move(triangles), {},
                                         std::move(pattern_to_garment), num_garment_vertices)),
                  rest, material) {}

void ClothEnergy::check_rest(const Points2& rest) const {
  const Triangles& triangles = topology_->pattern_triangles;
  if (rest.rows() != topology_->num_pattern_vertices())
    throw InputError(kClothSource, "rest positions have " + std::to_string(rest.rows()) +
                                       " rows, expected " +
                                       std::to_string(topology_->num_pattern_vertices()));
  for (Eigen::Index e = 0; e < triangles.rows(); ++e) {
    const Vec2 e1 = (rest.row(triangles(e, 1)) - rest.row(triangles(e, 0))).transpose();
    const Vec2 e2 = (rest.row(triangles(e, 2)) - rest.row(triangles(e, 0))).transpose();
    const double cross = e1.x() * e2.y() - e1.y() * e2.x();
    if (!(std::abs(cross) > 1e-14 * (e1.squaredNorm() + e2.squaredNorm())))
      throw InputError(kClothSource,
                       "rest triangle " + std::to_string(e) + " is degenerate (zero area)");
  }
}

void ClothEnergy::check_x(const VecX& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_garment_vertices()))
    throw std::invalid_argument("ClothEnergy: position vector has " + std::to_string(x.size()) +
                                " entries, expected 3 x " + std::to_string(num_garment_vertices()));
}

double ClothEnergy::rest_area(int e) const {
  const Vec2 e1 = (rest().row(triangles()(e, 1)) - rest().row(triangles()(e, 0))).transpose();
  const Vec2 e2 = (rest().row(triangles()(e, 2)) - rest().row(triangles()(e, 0))).transpose();
  return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
}

Mat32 ClothEnergy::deformation_gradient(const VecX& x, int e) const {
  Mat2 dm;
  Mat32 ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = (rest().row(triangles()(e, k + 1)) - rest().row(triangles()(e, 0))).transpose();
    ds.col(k) = x.segment<3>(3 * pattern_to_garment()[triangles()(e, k + 1)]) -
                x.segment<3>(3 * pattern_to_garment()[triangles()(e, 0)]);
  }
  return ds * dm.inverse();
}

namespace {

/// Per-element data gathered from the global arrays.
struct ClothElement {
  std::array<int, 3> garment;  // garment vertex ids
  std::array<int, 3> pattern;  // pattern vertex ids
  EdgeMetric<3> deformed;
  EdgeMetric<2> rest;
  std::array<Vec2, 3> rest_corners;
};

ClothElement gather_element(const Triangles& triangles, const Points2& rest,
                            const std::vector<int>& to_garment, const VecX& x, Eigen::Index e) {
  ClothElement el;
  for (int k = 0; k < 3; ++k) {
    el.pattern[k] = triangles(e, k);
    el.garment[k] = to_garment[el.pattern[k]];
  }
  el.deformed = edge_metric<3>(x.segment<3>(3 * el.garment[0]), x.segment<3>(3 * el.garment[1]),
                               x.segment<3>(3 * el.garment[2]));
  for (int k = 0; k < 3; ++k) el.rest_corners[k] = rest.row(el.pattern[k]).transpose();
  el.rest = edge_metric<2>(el.rest_corners[0], el.rest_corners[1], el.rest_corners[2]);
  return el;
}

/// The linear map c = L g from the deformed edge metric g = (G11, G22, G12) to the
/// material-frame strain components c = (C_xx, C_yy, C_xy) of C = Pᵀ G P, P = Dm⁻¹.
template <typename S>
Eigen::Matrix<S, 3, 3> strain_map(const autodiff::Mat2T<S>& p) {
  Eigen::Matrix<S, 3, 3> l;
  l << p(0, 0) * p(0, 0), p(1, 0) * p(1, 0), 2.0 * p(0, 0) * p(1, 0),  //
      p(0, 1) * p(0, 1), p(1, 1) * p(1, 1), 2.0 * p(0, 1) * p(1, 1),   //
      p(0, 0) * p(0, 1), p(1, 0) * p(1, 1), p(0, 0) * p(1, 1) + p(1, 0) * p(0, 1);
  return l;
}

/// Dm⁻¹ and the rest area |det Dm|/2 of rest corners r.
template <typename S>
std::pair<autodiff::Mat2T<S>, S> rest_frame(const std::array<autodiff::Vec2T<S>, 3>& r) {
  autodiff::Mat2T<S> dm;
  dm.col(0) = r[1] - r[0];
  dm.col(1) = r[2] - r[0];
  const S det = dm(0, 0) * dm(1, 1) - dm(0, 1) * dm(1, 0);
  return {autodiff::inverse2(dm), autodiff::value_of(det) >= 0.0 ? S(0.5 * det) : S(-0.5 * det)};
}

/// Φ of a measured (orthotropic) fabric element, per unit thickness: A W(c), c = L g. The
/// same layout as Phi over (g, rest metric) is not enough (the energy depends on the rest
/// triangle's orientation), so the rest derivatives are taken with respect to the three
/// rest corners: `rest_gradient` (6, with `rest_derivatives`) and `mixed` = ∂²Φ/∂g∂corners
/// (3×6, with `rest_derivatives` and order 2).
struct MeasuredPhi {
  Phi phi;  // value, and gradient/Hessian in g (the first three entries / top-left block)
  Vec6 rest_gradient = Vec6::Zero();
  Eigen::Matrix<double, 3, 6> mixed = Eigen::Matrix<double, 3, 6>::Zero();
};

MeasuredPhi measured_phi(const ClothElement& el, const FabricLaw& law, int order,
                         bool rest_derivatives) {
  MeasuredPhi out;
  const std::array<Vec2, 3>& r = el.rest_corners;
  const auto [p, area] = rest_frame<double>(r);
  const Mat3 l = strain_map<double>(p);
  const Vec3& g = el.deformed.value;
  const Vec3 c = l * g;
  const FabricLaw::Derivatives w = law.evaluate(c, rest_derivatives ? std::max(order, 1) : order);
  out.phi.value = area * w.value;
  if (order >= 1) out.phi.gradient.head<3>() = area * l.transpose() * w.gradient;
  if (order >= 2) out.phi.hessian.topLeftCorner<3, 3>() = area * l.transpose() * w.hessian * l;
  if (!rest_derivatives) return out;
  using S = autodiff::Scalar<6>;
  std::array<autodiff::Vec2T<S>, 3> ra;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 2; ++i) ra[k](i) = autodiff::variable<6>(r[k](i), 2 * k + i);
  const auto [ps, as] = rest_frame<S>(ra);
  const Eigen::Matrix<S, 3, 3> ls = strain_map<S>(ps);
  Eigen::Matrix<S, 3, 1> cs = ls * g.cast<S>();
  Eigen::Matrix<double, 3, 6> dc;
  for (int k = 0; k < 3; ++k) dc.row(k) = cs(k).derivatives().transpose();
  const S value(w.value, dc.transpose() * w.gradient);
  out.rest_gradient = (as * value).derivatives();
  if (order < 2) return out;  // the mixed derivative needs the law's Hessian
  Eigen::Matrix<S, 3, 1> grad;
  for (int k = 0; k < 3; ++k)
    grad(k) = S(w.gradient[k], dc.transpose() * w.hessian.row(k).transpose());
  const Eigen::Matrix<S, 3, 1> v = as * (ls.transpose() * grad);
  for (int k = 0; k < 3; ++k) out.mixed.row(k) = v(k).derivatives().transpose();
  return out;
}

/// True when the element Hessian t·(Jᵀ Φ_GG J + K(w) ⊗ I₃) is positive semi-definite by
/// construction: Φ_GG, the 3×3 Hessian in the deformed metric, has no negative principal
/// minor (Sylvester), and so has the stress W = [[2w₀, w₂], [w₂, 2w₁]], w = ∂Φ/∂G, of
/// which K = [s₁ s₂] W [s₁ s₂]ᵀ (metric_curvature). A sum of PSD terms needs no projection.
bool psd_by_construction(const Phi& phi) {
  const Vec3 w = phi.gradient.head<3>();
  if (!(w[0] >= 0.0 && w[1] >= 0.0 && 4.0 * w[0] * w[1] - w[2] * w[2] >= 0.0)) return false;
  const Mat3 h = phi.hessian.topLeftCorner<3, 3>();
  return h(0, 0) >= 0.0 && h(1, 1) >= 0.0 && h(2, 2) >= 0.0 &&
         h(0, 0) * h(1, 1) - h(0, 1) * h(0, 1) >= 0.0 &&
         h(0, 0) * h(2, 2) - h(0, 2) * h(0, 2) >= 0.0 &&
         h(1, 1) * h(2, 2) - h(1, 2) * h(1, 2) >= 0.0 && h.determinant() >= 0.0;
}

/// The element's 9×9 Hessian (over its three garment vertices), projected onto the PSD
/// cone with `project_psd` (an eigen-decomposition, skipped where the Hessian is PSD by
/// construction).
Mat9 cloth_element_hessian(const ClothElement& el, const FabricLaw& law, bool project_psd) {
  const Phi phi = law.measured()
                      ? measured_phi(el, law, 2, false).phi
                      : element_phi(el.deformed.value, el.rest.value, law.isotropic(), 2);
  const Mat3x9& j = el.deformed.jacobian;
  Mat9 local = law.material().thickness * (j.transpose() * phi.hessian.topLeftCorner<3, 3>() * j +
                                           metric_curvature<3>(phi.gradient.head<3>()));
  if (project_psd && !psd_by_construction(phi)) tightfit::project_psd(local);
  return local;
}

/// Runs fn(e, element) for every triangle in parallel (parallel_for: fn writes only to
/// element e's slots).
template <typename Fn>
void for_each_element(const Triangles& triangles, const Points2& rest,
                      const std::vector<int>& to_garment, const VecX& x, Fn&& fn) {
  parallel_for(triangles.rows(),
               [&](std::int64_t e) { fn(e, gather_element(triangles, rest, to_garment, x, e)); });
}

/// g += Σ_e local_e scattered over each element's vertex ids (Dim DOFs per vertex):
/// `compute(e, element, local, ids)` fills element e's slot in parallel, the scatter is
/// serial in element order (the same sums for every thread count).
template <int Dim, typename Compute>
void assemble_gradient(const Triangles& triangles, const Points2& rest,
                       const std::vector<int>& to_garment, const VecX& x, VecX& g,
                       Compute&& compute) {
  std::vector<Eigen::Matrix<double, 3 * Dim, 1>> local(static_cast<size_t>(triangles.rows()));
  std::vector<std::array<int, 3>> ids(local.size());
  for_each_element(triangles, rest, to_garment, x, [&](std::int64_t e, const ClothElement& el) {
    compute(el, local[static_cast<size_t>(e)], ids[static_cast<size_t>(e)]);
  });
  for (size_t e = 0; e < local.size(); ++e) scatter_gradient<Dim>(ids[e], local[e], g);
}

}  // namespace

double ClothEnergy::value(const VecX& x) const {
  check_x(x);
  VecX values(triangles().rows());
  for_each_element(
      triangles(), rest(), pattern_to_garment(), x, [&](std::int64_t e, const ClothElement& el) {
        values[e] = law_.measured()
                        ? measured_phi(el, law_, 0, false).phi.value
                        : element_phi(el.deformed.value, el.rest.value, law_.isotropic(), 0).value;
      });
  return material().thickness * values.sum();
}

void ClothEnergy::add_gradient(const VecX& x, VecX& g) const {
  check_x(x);
  check_x(g);
  const double t = material().thickness;
  assemble_gradient<3>(triangles(), rest(), pattern_to_garment(), x, g,
                       [&](const ClothElement& el, Vec9& local, std::array<int, 3>& ids) {
                         const Phi phi = law_.measured()
                                             ? measured_phi(el, law_, 1, false).phi
                                             : element_phi(el.deformed.value, el.rest.value,
                                                           law_.isotropic(), 1);
                         local = t * el.deformed.jacobian.transpose() * phi.gradient.head<3>();
                         ids = el.garment;
                       });
}

void ClothEnergy::add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd) const {
  check_x(x);
  constexpr size_t kPerElement = 81;
  const size_t first = H.size();
  H.resize(first + kPerElement * static_cast<size_t>(triangles().rows()));
  for_each_element(triangles(), rest(), pattern_to_garment(), x,
                   [&](std::int64_t e, const ClothElement& el) {
                     scatter_hessian<3>(el.garment, cloth_element_hessian(el, law_, project_psd),
                                        H.data() + first + kPerElement * static_cast<size_t>(e));
                   });
}

bool ClothEnergy::add_element_hessians(const VecX& x, std::vector<ElementMatrices>& H,
                                       bool project_psd) const {
  check_x(x);
  std::vector<int> vertices(3 * static_cast<std::size_t>(triangles().rows()));
  for (Eigen::Index e = 0; e < triangles().rows(); ++e)
    for (int k = 0; k < 3; ++k)
      vertices[3 * static_cast<std::size_t>(e) + k] = pattern_to_garment()[triangles()(e, k)];
  ElementMatrices& out = H.emplace_back(3, std::move(vertices));
  for_each_element(triangles(), rest(), pattern_to_garment(), x,
                   [&](std::int64_t e, const ClothElement& el) {
                     Eigen::Map<Mat9>(out.matrix(e)) = cloth_element_hessian(el, law_, project_psd);
                   });
  return true;
}

void ClothEnergy::add_gradient_rest(const VecX& x, VecX& g_rest) const {
  check_x(x);
  if (g_rest.size() != 2 * rest().rows())
    throw std::invalid_argument("ClothEnergy::add_gradient_rest: wrong vector size");
  const double t = material().thickness;
  assemble_gradient<2>(triangles(), rest(), pattern_to_garment(), x, g_rest,
                       [&](const ClothElement& el, Vec6& local, std::array<int, 3>& ids) {
                         if (law_.measured()) {
                           local = t * measured_phi(el, law_, 1, true).rest_gradient;
                         } else {
                           const Phi phi =
                               element_phi(el.deformed.value, el.rest.value, law_.isotropic(), 1);
                           local = t * el.rest.jacobian.transpose() * phi.gradient.tail<3>();
                         }
                         ids = el.pattern;
                       });
}

void ClothEnergy::add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const {
  check_x(x);
  constexpr size_t kPerElement = 54;
  const size_t first = H.size();
  H.resize(first + kPerElement * static_cast<size_t>(triangles().rows()));
  const double t = material().thickness;
  for_each_element(
      triangles(), rest(), pattern_to_garment(), x, [&](std::int64_t e, const ClothElement& el) {
        Eigen::Matrix<double, 3, 6> mixed;
        if (law_.measured()) {
          mixed = measured_phi(el, law_, 2, true).mixed;
        } else {
          const Phi phi = element_phi(el.deformed.value, el.rest.value, law_.isotropic(), 2);
          mixed = phi.hessian.topRightCorner<3, 3>() * el.rest.jacobian;
        }
        const Eigen::Matrix<double, 9, 6> local = t * el.deformed.jacobian.transpose() * mixed;
        scatter_block<3, 3, 2, 3>(el.garment, el.pattern, local,
                                  H.data() + first + kPerElement * static_cast<size_t>(e));
      });
}

}  // namespace tightfit
