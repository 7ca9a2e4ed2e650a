#include "tightfit/objectives/seam_traction_objective.hpp"

#include <stdexcept>
#include <string>

#include "tightfit/physics/autodiff.hpp"

namespace tightfit {

using namespace autodiff;  // NOLINT: the AD helper types

SeamTractionObjective::SeamTractionObjective(const Garment& garment, const ClothMaterial& material)
    : topology_(garment.topology),
      num_garment_(garment.num_garment_vertices()),
      num_pattern_(garment.num_pattern_vertices()),
      law_(material),
      elements_(seam_elements(*garment.topology)) {}

void SeamTractionObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument("seam traction objective: state has " +
                                std::to_string(state.x.size()) + " position entries and " +
                                std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

VecX SeamTractionObjective::tractions(const DesignState& state) const {
  check(state);
  return seam_normal_tractions(*topology_, elements_, law_, state.x, state.rest);
}

double SeamTractionObjective::value(const DesignState& state) const {
  check(state);
  double total = 0.0;
  for (const SeamElement& el : elements_) {
    std::array<Vec3, 3> x;
    std::array<Vec2, 3> r;
    for (int k = 0; k < 3; ++k) {
      x[k] = state.x.segment<3>(
          3 * topology_->pattern_to_garment[topology_->pattern_triangles(el.triangle, k)]);
      r[k] = state.rest.row(topology_->pattern_triangles(el.triangle, k)).transpose();
    }
    total += seam_traction_term<double>(
        law_, x, r, triangle_corner(topology_->pattern_triangles, el.triangle, el.edge[0]),
        triangle_corner(topology_->pattern_triangles, el.triangle, el.edge[1]), false);
  }
  return total;
}

void SeamTractionObjective::add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const {
  check(state);
  if (d_x.size() != state.x.size() || d_rest.size() != 2 * state.rest.rows())
    throw std::invalid_argument("seam traction objective: gradient vectors have the wrong size");
  constexpr int kN = 15;  // 9 positions, 6 rest coordinates
  using S = Scalar<kN>;
  for (const SeamElement& el : elements_) {
    std::array<Vec3T<S>, 3> x;
    std::array<Vec2T<S>, 3> r;
    for (int k = 0; k < 3; ++k) {
      const int pv = topology_->pattern_triangles(el.triangle, k);
      const int gv = topology_->pattern_to_garment[pv];
      for (int c = 0; c < 3; ++c) x[k](c) = variable<kN>(state.x[3 * gv + c], 3 * k + c);
      for (int c = 0; c < 2; ++c) r[k](c) = variable<kN>(state.rest(pv, c), 9 + 2 * k + c);
    }
    const S t = seam_traction_term<S>(
        law_, x, r, triangle_corner(topology_->pattern_triangles, el.triangle, el.edge[0]),
        triangle_corner(topology_->pattern_triangles, el.triangle, el.edge[1]), false);
    const Eigen::Matrix<double, kN, 1>& g = t.derivatives();
    for (int k = 0; k < 3; ++k) {
      const int pv = topology_->pattern_triangles(el.triangle, k);
      d_x.segment<3>(3 * topology_->pattern_to_garment[pv]) += g.segment<3>(3 * k);
      d_rest.segment<2>(2 * pv) += g.segment<2>(9 + 2 * k);
    }
  }
}

}  // namespace tightfit
