#include "tightfit/solve/embedded_equilibrium.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "tightfit/common/error.hpp"
#include "tightfit/common/parallel.hpp"

namespace tightfit {
namespace {

VecX flat(const Points3& p) { return Eigen::Map<const VecX>(p.data(), p.size()); }

/// Σ of the energies' Hessians at x over `num_vertices` vertices: element by element
/// where an energy offers it, as triplets otherwise.
BlockSparseMatrix3 assemble_hessian(const std::vector<const Energy*>& energies, const VecX& x,
                                    int num_vertices, bool project,
                                    std::shared_ptr<const BlockLayout> layout) {
  std::vector<ElementMatrices> elements;
  std::vector<Triplet> triplets;
  for (const Energy* energy : energies)
    if (!energy->add_element_hessians(x, elements, project))
      energy->add_hessian(x, triplets, project);
  return BlockSparseMatrix3::assemble(elements, triplets, num_vertices, std::move(layout));
}

}  // namespace

EmbeddedEquilibrium::EmbeddedEquilibrium(EmbeddedSystemSetup setup, EmbeddedState initial)
    : setup_(std::move(setup)), base_(std::move(initial)), state_(base_) {
  if (!setup_.surface) throw SolverError("EmbeddedEquilibrium: no limit surface");
  if (!setup_.hessian_layouts) setup_.hessian_layouts = std::make_shared<HessianLayouts>();
  num_control_ = setup_.surface->num_control_vertices();
  if (state_.body.rows() < num_control_)
    throw SolverError("EmbeddedEquilibrium: body has fewer vertices than the surface");
  const int ng = num_garment_vertices();
  const int nb = static_cast<int>(state_.body.rows());
  std::vector<char> garment_pinned(ng, 0), body_pinned(nb, 0);
  for (int i : setup_.pinned_garment) {
    if (i < 0 || i >= ng)
      throw SolverError("EmbeddedEquilibrium: pinned garment index out of range");
    garment_pinned[i] = 1;
  }
  for (int k : setup_.pinned_body) {
    if (k < 0 || k >= nb) throw SolverError("EmbeddedEquilibrium: pinned body index out of range");
    body_pinned[k] = 1;
  }
  garment_dof_.assign(ng, -1);
  body_dof_.assign(nb, -1);
  int next = 0;
  for (int i = 0; i < ng; ++i)
    if (!garment_pinned[i]) {
      garment_dof_[i] = next;
      next += 2;
    }
  for (int k = 0; k < nb; ++k)
    if (!body_pinned[k]) {
      body_dof_[k] = next;
      next += 3;
    }
  num_dofs_ = next;
  evaluate_garment();
}

void EmbeddedEquilibrium::evaluate_garment() {
  const int ng = num_garment_vertices();
  weights_.resize(ng);
  for (Points3* p : {&x_, &xu_, &xv_, &xuu_, &xuv_, &xvv_}) p->setZero(ng, 3);
  parallel_for(ng, [&](std::int64_t i) {
    LimitWeights& w = weights_[i];
    setup_.surface->weights(state_.garment[i], w);
    for (size_t j = 0; j < w.index.size(); ++j) {
      const auto y = state_.body.row(w.index[j]);
      x_.row(i) += w.p[j] * y;
      xu_.row(i) += w.du[j] * y;
      xv_.row(i) += w.dv[j] * y;
      xuu_.row(i) += w.duu[j] * y;
      xuv_.row(i) += w.duv[j] * y;
      xvv_.row(i) += w.dvv[j] * y;
    }
  });
}

double EmbeddedEquilibrium::garment_energy(const VecX& x) const {
  double e = 0.0;
  for (const Energy* energy : setup_.garment_energies) e += energy->value(x);
  return e;
}

double EmbeddedEquilibrium::energy() {
  double e = garment_energy(flat(x_));
  const VecX y = flat(state_.body);
  for (const Energy* energy : setup_.body_energies) e += energy->value(y);
  return e;
}

VecX EmbeddedEquilibrium::garment_energy_gradient() const {
  const VecX x = flat(x_);
  VecX gx = VecX::Zero(x.size());
  for (const Energy* energy : setup_.garment_energies) energy->add_gradient(x, gx);
  return gx;
}

VecX EmbeddedEquilibrium::gradient() { return total_gradient(); }

VecX EmbeddedEquilibrium::total_gradient() const {
  const VecX gx = garment_energy_gradient();
  const VecX y = flat(state_.body);
  VecX gy = VecX::Zero(y.size());
  for (const Energy* energy : setup_.body_energies) energy->add_gradient(y, gy);
  VecX g = VecX::Zero(num_dofs_);
  for (int i = 0; i < num_garment_vertices(); ++i) {
    const Vec3 gi = gx.segment<3>(3 * i);
    if (const int d = garment_dof_[i]; d >= 0) {
      g[d] += xu_.row(i).dot(gi);
      g[d + 1] += xv_.row(i).dot(gi);
    }
    const LimitWeights& w = weights_[i];
    for (size_t j = 0; j < w.index.size(); ++j) gy.segment<3>(3 * w.index[j]) += w.p[j] * gi;
  }
  for (int k = 0; k < static_cast<int>(body_dof_.size()); ++k)
    if (const int d = body_dof_[k]; d >= 0) g.segment<3>(d) += gy.segment<3>(3 * k);
  return g;
}

SparseMatrix EmbeddedEquilibrium::position_jacobian() const {
  std::vector<Triplet> t;
  for (int i = 0; i < num_garment_vertices(); ++i) {
    if (const int d = garment_dof_[i]; d >= 0)
      for (int c = 0; c < 3; ++c) {
        t.emplace_back(3 * i + c, d, xu_(i, c));
        t.emplace_back(3 * i + c, d + 1, xv_(i, c));
      }
    const LimitWeights& w = weights_[i];
    for (size_t j = 0; j < w.index.size(); ++j)
      if (const int d = body_dof_[w.index[j]]; d >= 0)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * i + c, d + c, w.p[j]);
  }
  SparseMatrix J(3 * num_garment_vertices(), num_dofs_);
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

SparseMatrix EmbeddedEquilibrium::hessian(HessianKind kind) {
  return CoupledHessian(hessian_factors(kind)).matrix();
}

LinearOperator EmbeddedEquilibrium::hessian_operator(HessianKind kind) {
  auto hessian = std::make_shared<const CoupledHessian>(hessian_factors(kind));
  return LinearOperator([hessian](const VecX& v) { return hessian->multiply(v); });
}

CoupledHessianFactors EmbeddedEquilibrium::hessian_factors(HessianKind kind) const {
  const int ng = num_garment_vertices();
  const bool project = kind == HessianKind::kNewton && setup_.project_garment_hessians;
  CoupledHessianFactors f;
  f.num_dofs = num_dofs_;
  f.garment_dof = garment_dof_;
  f.body_dof = body_dof_;
  HessianLayouts& layouts = *setup_.hessian_layouts;
  f.garment = assemble_hessian(setup_.garment_energies, flat(x_), ng, project, layouts.garment);
  layouts.garment = f.garment.layout();
  // The body's Hessian only where a body vertex is free (a rigid body has none).
  if (std::any_of(body_dof_.begin(), body_dof_.end(), [](int d) { return d >= 0; })) {
    f.body = assemble_hessian(setup_.body_energies, flat(state_.body),
                              static_cast<int>(state_.body.rows()), false, layouts.body);
    layouts.body = f.body.layout();
  }

  // J's rows and the second-derivative terms of Eq. 18 contracted with dU/dx.
  const VecX gx = garment_energy_gradient();
  f.garment_forces = Eigen::Map<const Points3>(gx.data(), ng, 3);
  f.tangents.resize(ng);
  f.curvature_terms.resize(ng);
  f.stencil_start.assign(static_cast<std::size_t>(ng) + 1, 0);
  for (int i = 0; i < ng; ++i) f.stencil_start[i + 1] = f.stencil_start[i] + weights_[i].size();
  const auto entries = static_cast<std::size_t>(f.stencil_start[ng]);
  f.stencil_vertex.resize(entries);
  f.weight.resize(entries);
  f.weight_u.resize(entries);
  f.weight_v.resize(entries);
  for (int i = 0; i < ng; ++i) {
    f.tangents[i] = tangent_basis(i);
    const Vec3 gi = gx.segment<3>(3 * i);
    const double huv = xuv_.row(i).dot(gi);
    f.curvature_terms[i] << xuu_.row(i).dot(gi), huv, huv, xvv_.row(i).dot(gi);
    const LimitWeights& w = weights_[i];
    const auto first = static_cast<std::ptrdiff_t>(f.stencil_start[i]);
    std::copy(w.index.begin(), w.index.end(), f.stencil_vertex.begin() + first);
    std::copy(w.p.begin(), w.p.end(), f.weight.begin() + first);
    std::copy(w.du.begin(), w.du.end(), f.weight_u.begin() + first);
    std::copy(w.dv.begin(), w.dv.end(), f.weight_v.begin() + first);
  }
  return f;
}

bool EmbeddedEquilibrium::set_step(const VecX& dq, double alpha) {
  // Per garment vertex: 1 when its walk stopped at a surface vertex before the end of
  // its displacement. Such a state is not (committed state) ⊕ alpha·dq: refused.
  std::vector<char> blocked(static_cast<std::size_t>(num_garment_vertices()), 0);
  parallel_for(num_garment_vertices(), [&](std::int64_t i) {
    const int d = garment_dof_[i];
    if (d < 0) {
      state_.garment[i] = base_.garment[i];
      return;
    }
    const Vec2 delta = alpha * dq.segment<2>(d);
    const LimitSurface::Walk walk = setup_.surface->walk(base_.garment[i], delta);
    state_.garment[i] = walk.end;
    blocked[static_cast<std::size_t>(i)] = walk.complete ? 0 : 1;
  });
  for (int k = 0; k < static_cast<int>(body_dof_.size()); ++k) {
    const int d = body_dof_[k];
    state_.body.row(k) = base_.body.row(k);
    if (d >= 0) state_.body.row(k) += alpha * dq.segment<3>(d).transpose();
  }
  evaluate_garment();
  return std::find(blocked.begin(), blocked.end(), 1) == blocked.end();
}

void EmbeddedEquilibrium::commit() { base_ = state_; }

Eigen::Matrix<double, 3, 2> EmbeddedEquilibrium::tangent_basis(int i) const {
  Eigen::Matrix<double, 3, 2> Js;
  Js.col(0) = xu_.row(i).transpose();
  Js.col(1) = xv_.row(i).transpose();
  return Js;
}

double EmbeddedEquilibrium::tangential_force_squared(int i, const VecX& g) const {
  // Tangential force f with g_s = J_sᵀ f, f in the tangent plane: |f|² = g_sᵀ (J_sᵀJ_s)⁻¹ g_s.
  const Eigen::Matrix<double, 3, 2> Js = tangent_basis(i);
  const Mat2 metric = Js.transpose() * Js;
  const Vec2 gs = g.segment<2>(garment_dof_[i]);
  return gs.dot(metric.ldlt().solve(gs));
}

double EmbeddedEquilibrium::force_norm(const VecX& g) {
  double sum = 0.0;
  for (int i = 0; i < num_garment_vertices(); ++i)
    if (garment_dof_[i] >= 0) sum += tangential_force_squared(i, g);
  for (int k = 0; k < static_cast<int>(body_dof_.size()); ++k)
    if (const int d = body_dof_[k]; d >= 0) sum += g.segment<3>(d).squaredNorm();
  return std::sqrt(sum);
}

Points3 EmbeddedEquilibrium::garment_residual_forces() const {
  const VecX g = total_gradient();
  Points3 f = Points3::Zero(num_garment_vertices(), 3);
  for (int i = 0; i < num_garment_vertices(); ++i) {
    const int d = garment_dof_[i];
    if (d < 0) continue;
    const Eigen::Matrix<double, 3, 2> Js = tangent_basis(i);
    const Vec2 gs = g.segment<2>(d);
    f.row(i) = -(Js * (Js.transpose() * Js).ldlt().solve(gs)).transpose();
  }
  return f;
}

Points3 EmbeddedEquilibrium::body_residual_forces() const {
  const VecX g = total_gradient();
  Points3 f = Points3::Zero(static_cast<Eigen::Index>(body_dof_.size()), 3);
  for (int k = 0; k < static_cast<int>(body_dof_.size()); ++k)
    if (const int d = body_dof_[k]; d >= 0) f.row(k) = -g.segment<3>(d).transpose();
  return f;
}

std::string EmbeddedEquilibrium::locate_largest_force(const VecX& g) {
  if (g.size() != num_dofs_) return {};
  double largest = -1.0;
  int garment = -1, body = -1;
  for (int i = 0; i < num_garment_vertices(); ++i)
    if (garment_dof_[i] >= 0)
      if (const double f = tangential_force_squared(i, g); f > largest) {
        largest = f;
        garment = i;
      }
  for (int k = 0; k < static_cast<int>(body_dof_.size()); ++k)
    if (const int d = body_dof_[k]; d >= 0)
      if (const double f = g.segment<3>(d).squaredNorm(); f > largest) {
        largest = f;
        garment = -1;
        body = k;
      }
  if (largest < 0.0 || !std::isfinite(largest)) return {};
  std::ostringstream out;
  out.precision(3);
  out << std::sqrt(largest) << " N on ";
  Vec3 at;
  if (garment >= 0) {
    out << "garment vertex " << garment;
    if (const std::string label = garment_vertex_label(garment); !label.empty())
      out << " (" << label << ")";
    at = x_.row(garment).transpose();
  } else {
    out << (body < num_control_ ? "body surface vertex " : "body interior vertex ") << body;
    at = state_.body.row(body).transpose();
  }
  out << " at (" << at.x() << ", " << at.y() << ", " << at.z() << ") m";
  return out.str();
}

std::string EmbeddedEquilibrium::garment_vertex_label(int i) const {
  return setup_.garment_vertex_label ? setup_.garment_vertex_label(i) : std::string();
}

Vec3 EmbeddedEquilibrium::garment_normal(int i) const {
  return xu_.row(i).cross(xv_.row(i)).normalized();
}

}  // namespace tightfit
