#include "tightfit/physics/neo_hookean_energy.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "tightfit/common/error.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit {
namespace {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat9x12 = Eigen::Matrix<double, 9, 12>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

const std::string kNeoHookeanSource = "body tet mesh";

Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// Cofactor matrix of F (= J F^-T), column j = cross product of the other two columns.
Mat3 cofactor(const Mat3& F) {
  Mat3 c;
  c.col(0) = F.col(1).cross(F.col(2));
  c.col(1) = F.col(2).cross(F.col(0));
  c.col(2) = F.col(0).cross(F.col(1));
  return c;
}

/// d²J/dvec(F)² (column-major vec), J = det F.
Mat9 det_hessian(const Mat3& F) {
  Mat9 h = Mat9::Zero();
  const Mat3 x0 = cross_matrix(F.col(0));
  const Mat3 x1 = cross_matrix(F.col(1));
  const Mat3 x2 = cross_matrix(F.col(2));
  h.block<3, 3>(0, 3) = -x2;
  h.block<3, 3>(3, 0) = x2;
  h.block<3, 3>(0, 6) = x1;
  h.block<3, 3>(6, 0) = -x1;
  h.block<3, 3>(3, 6) = -x0;
  h.block<3, 3>(6, 3) = x0;
  return h;
}

/// Dᵀ h D (12×12), D = dvec(F)/dx the 9×12 Jacobian of F = Σ_a x_a ∇N_aᵀ (`grad_n` holds
/// ∇N_a in column a), without forming D: D(i + 3j, 3a + i) = ∇N_a[j], so block (a, b) is
/// Σ_{j,m} ∇N_a[j] ∇N_b[m] h_[j,m], h_[j,m] the 3×3 block of h at rows 3j, columns 3m:
/// about a third of the multiplications of the dense product, and no general matrix
/// product kernel for 12×9×9 sizes.
Mat12 pull_back_hessian(const Mat9& h, const Eigen::Matrix<double, 3, 4>& grad_n) {
  Mat9x12 h_d;  // h · D
  for (int b = 0; b < 4; ++b)
    h_d.middleCols<3>(3 * b).noalias() = grad_n(0, b) * h.middleCols<3>(0) +
                                         grad_n(1, b) * h.middleCols<3>(3) +
                                         grad_n(2, b) * h.middleCols<3>(6);
  Mat12 local;
  for (int a = 0; a < 4; ++a)
    local.middleRows<3>(3 * a).noalias() = grad_n(0, a) * h_d.middleRows<3>(0) +
                                           grad_n(1, a) * h_d.middleRows<3>(3) +
                                           grad_n(2, a) * h_d.middleRows<3>(6);
  return local;
}

Eigen::Matrix<double, 3, 4> shape_gradients(const Mat3& rest_inverse) {
  Eigen::Matrix<double, 3, 4> g;
  g.rightCols<3>() = rest_inverse.transpose();
  g.col(0) = -g.rightCols<3>().rowwise().sum();
  return g;
}

}  // namespace

NeoHookeanEnergy::NeoHookeanEnergy(const Points3& rest, const Tetrahedra& tets,
                                   NeoHookeanMaterial material)
    : num_vertices_(static_cast<int>(rest.rows())), material_(material) {
  if (!(material.youngs_modulus > 0.0) || !(material.poisson_ratio > -1.0) ||
      !(material.poisson_ratio < 0.5))
    throw InputError("body material", "needs E > 0 and -1 < nu < 0.5");
  mu_ = material.shear_modulus();
  kappa_ = material.bulk_modulus();
  tets_.reserve(tets.rows());
  rest_inverse_.reserve(tets.rows());
  volume_.reserve(tets.rows());
  for (Eigen::Index e = 0; e < tets.rows(); ++e) {
    std::array<int, 4> t{};
    for (int k = 0; k < 4; ++k) {
      t[k] = tets(e, k);
      if (t[k] < 0 || t[k] >= num_vertices_)
        throw InputError(kNeoHookeanSource, "tet " + std::to_string(e) + " has vertex index " +
                                                std::to_string(t[k]) + " outside [0, " +
                                                std::to_string(num_vertices_) + ")");
    }
    Mat3 dm;
    for (int k = 0; k < 3; ++k) dm.col(k) = (rest.row(t[k + 1]) - rest.row(t[0])).transpose();
    const double v = dm.determinant() / 6.0;
    if (!(v > 0.0))
      throw InputError(kNeoHookeanSource, "tet " + std::to_string(e) +
                                              " has non-positive rest volume (inverted or flat)");
    tets_.push_back(t);
    rest_inverse_.push_back(dm.inverse());
    volume_.push_back(v);
  }
}

void NeoHookeanEnergy::check_size(const VecX& v) const {
  if (v.size() != 3 * static_cast<Eigen::Index>(num_vertices_))
    throw std::invalid_argument("NeoHookeanEnergy: vector has " + std::to_string(v.size()) +
                                " entries, expected 3 x " + std::to_string(num_vertices_));
}

Mat3 NeoHookeanEnergy::deformation_gradient(const VecX& x, int e) const {
  const auto& t = tets_[e];
  Mat3 ds;
  for (int k = 0; k < 3; ++k) ds.col(k) = x.segment<3>(3 * t[k + 1]) - x.segment<3>(3 * t[0]);
  return ds * rest_inverse_[e];
}

double NeoHookeanEnergy::value(const VecX& x) const {
  check_size(x);
  VecX values(num_tets());
  parallel_for(num_tets(), [&](std::int64_t e) {
    const Mat3 F = deformation_gradient(x, static_cast<int>(e));
    const double J = F.determinant();
    if (!(J > 0.0)) {
      values[e] = std::numeric_limits<double>::infinity();
      return;
    }
    const double w = 0.5 * mu_ * (std::pow(J, -2.0 / 3.0) * F.squaredNorm() - 3.0) +
                     0.5 * kappa_ * (J - 1.0) * (J - 1.0);
    values[e] = volume_[e] * w;
  });
  double total = 0.0;
  for (Eigen::Index e = 0; e < values.size(); ++e) {
    if (values[e] == std::numeric_limits<double>::infinity()) return values[e];
    total += values[e];
  }
  return total;
}

void NeoHookeanEnergy::add_gradient(const VecX& x, VecX& g) const {
  check_size(x);
  check_size(g);
  std::vector<Eigen::Matrix<double, 3, 4>> local(tets_.size());
  parallel_for(num_tets(), [&](std::int64_t e) {
    const Mat3 F = deformation_gradient(x, static_cast<int>(e));
    const double J = F.determinant();
    if (!(J > 0.0))
      throw SolverError("NeoHookeanEnergy: gradient at inverted tet " + std::to_string(e));
    const double a = std::pow(J, -2.0 / 3.0);
    const double i1 = F.squaredNorm();
    const Mat3 cof = cofactor(F);
    const Mat3 P = mu_ * a * F + (kappa_ * (J - 1.0) - mu_ * a * i1 / (3.0 * J)) * cof;
    // dU/dx_a = V P ∇N_a.
    local[e] = volume_[e] * P * shape_gradients(rest_inverse_[e]);
  });
  for (size_t e = 0; e < tets_.size(); ++e)
    for (int k = 0; k < 4; ++k) g.segment<3>(3 * tets_[e][k]) += local[e].col(k);
}

Mat12 NeoHookeanEnergy::element_hessian(const VecX& x, int e, bool project_psd) const {
  const Mat3 F = deformation_gradient(x, e);
  const double J = F.determinant();
  if (!(J > 0.0))
    throw SolverError("NeoHookeanEnergy: Hessian at inverted tet " + std::to_string(e));
  const double a = std::pow(J, -2.0 / 3.0);
  const double i1 = F.squaredNorm();
  const Vec9 f = Eigen::Map<const Vec9>(F.data());
  const Mat3 cof_m = cofactor(F);
  const Vec9 c = Eigen::Map<const Vec9>(cof_m.data());
  Mat9 h = mu_ * a * Mat9::Identity();
  h -= (2.0 / 3.0) * mu_ * a / J * (f * c.transpose() + c * f.transpose());
  h += ((5.0 / 9.0) * mu_ * a * i1 / (J * J) + kappa_) * c * c.transpose();
  h += (kappa_ * (J - 1.0) - mu_ * a * i1 / (3.0 * J)) * det_hessian(F);
  Mat12 local = volume_[e] * pull_back_hessian(h, shape_gradients(rest_inverse_[e]));
  if (project_psd) tightfit::project_psd(local);
  return local;
}

void NeoHookeanEnergy::add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd) const {
  check_size(x);
  constexpr size_t kPerElement = 144;
  const size_t first = H.size();
  H.resize(first + kPerElement * tets_.size());
  parallel_for(num_tets(), [&](std::int64_t e) {
    scatter_hessian<3>(tets_[e], element_hessian(x, static_cast<int>(e), project_psd),
                       H.data() + first + kPerElement * static_cast<size_t>(e));
  });
}

bool NeoHookeanEnergy::add_element_hessians(const VecX& x, std::vector<ElementMatrices>& H,
                                            bool project_psd) const {
  check_size(x);
  std::vector<int> vertices;
  vertices.reserve(4 * tets_.size());
  for (const auto& t : tets_) vertices.insert(vertices.end(), t.begin(), t.end());
  ElementMatrices& out = H.emplace_back(4, std::move(vertices));
  parallel_for(num_tets(), [&](std::int64_t e) {
    Eigen::Map<Mat12>(out.matrix(e)) = element_hessian(x, static_cast<int>(e), project_psd);
  });
  return true;
}

}  // namespace tightfit
