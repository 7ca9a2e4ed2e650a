#include "tightfit/objectives/regularizer_smoothness.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/objectives/rest_term_checks.hpp"

namespace tightfit {
namespace {

/// Whether the turn at a vertex is too close to a fold-back to evaluate κ.
bool folded(double l1, double l2, double den) { return !(den > 1e-14 * l1 * l2); }

}  // namespace

BoundarySmoothnessRegularizer::BoundarySmoothnessRegularizer(const Garment& garment)
    : num_pattern_(garment.num_pattern_vertices()) {
  triples_ = boundary_triples(garment, BoundaryVertices::kAllButCorners);
}

double BoundarySmoothnessRegularizer::value(const DesignState& state) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  double total = 0.0;
  for (const auto& t : triples_) {
    const Vec2 e1 = (state.rest.row(t[1]) - state.rest.row(t[0])).transpose();
    const Vec2 e2 = (state.rest.row(t[2]) - state.rest.row(t[1])).transpose();
    const double l1 = e1.norm(), l2 = e2.norm();
    const double den = l1 * l2 + e1.dot(e2);
    if (folded(l1, l2, den)) return std::numeric_limits<double>::infinity();
    const double kappa = 2.0 * cross2(e1, e2) / den;
    total += kappa * kappa / (l1 + l2);
  }
  return total;
}

void BoundarySmoothnessRegularizer::add_gradient(const DesignState& state, VecX& /*d_x*/,
                                                 VecX& d_rest) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  check_rest_gradient_size(name(), d_rest, num_pattern_);
  for (const auto& t : triples_) {
    const Vec2 e1 = (state.rest.row(t[1]) - state.rest.row(t[0])).transpose();
    const Vec2 e2 = (state.rest.row(t[2]) - state.rest.row(t[1])).transpose();
    const double l1 = e1.norm(), l2 = e2.norm();
    const double den = l1 * l2 + e1.dot(e2);
    if (folded(l1, l2, den))
      throw SolverError("boundary smoothness: the boundary folds back at pattern vertex " +
                        std::to_string(t[1]));
    const double cr = cross2(e1, e2);
    const double kappa = 2.0 * cr / den;
    const double sum = l1 + l2;
    // R = κ²/s: dR = (2κ/s) dκ − (κ²/s²)(dl1 + dl2), dκ = 2 dcr/den − 2 cr dden/den².
    const double c_kappa = 2.0 * kappa / sum;
    const double c_len = -kappa * kappa / (sum * sum);
    const Vec2 dcr1(e2.y(), -e2.x()), dcr2(-e1.y(), e1.x());
    const Vec2 dden1 = l2 / l1 * e1 + e2, dden2 = l1 / l2 * e2 + e1;
    const Vec2 g1 = c_kappa * (2.0 * dcr1 / den - 2.0 * cr * dden1 / (den * den)) + c_len * e1 / l1;
    const Vec2 g2 = c_kappa * (2.0 * dcr2 / den - 2.0 * cr * dden2 / (den * den)) + c_len * e2 / l2;
    d_rest.segment<2>(2 * t[0]) -= g1;
    d_rest.segment<2>(2 * t[1]) += g1 - g2;
    d_rest.segment<2>(2 * t[2]) += g2;
  }
}

}  // namespace tightfit
