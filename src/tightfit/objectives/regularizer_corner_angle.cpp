#include "tightfit/objectives/regularizer_corner_angle.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/objectives/rest_term_checks.hpp"

namespace tightfit {
namespace {

/// The two boundary edges at a corner (incoming, outgoing).
struct CornerEdges {
  Vec2 in;
  Vec2 out;
};

CornerEdges edges_at(const Points2& rest, const std::array<int, 3>& t) {
  return {(rest.row(t[1]) - rest.row(t[0])).transpose(),
          (rest.row(t[2]) - rest.row(t[1])).transpose()};
}

/// Turning angle (rad, in (−π, π]) from edge `in` to edge `out`.
double turning_angle(const CornerEdges& e) {
  return std::atan2(cross2(e.in, e.out), e.in.dot(e.out));
}

/// θ − θ⁰ taken into (−π, π], so that a corner turning through ±π is not a jump of 2π.
double angle_difference(double theta, double reference) {
  double d = theta - reference;
  if (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
  if (d <= -std::numbers::pi) d += 2.0 * std::numbers::pi;
  return d;
}

bool degenerate(const CornerEdges& e) { return !(e.in.norm() > 0.0 && e.out.norm() > 0.0); }

}  // namespace

CornerAngleRegularizer::CornerAngleRegularizer(const Garment& garment)
    : num_pattern_(garment.num_pattern_vertices()) {
  const Points2 rest = garment.rest_positions();
  triples_ = boundary_triples(garment, BoundaryVertices::kCorners);
  for (const std::array<int, 3>& t : triples_) {
    const CornerEdges e = edges_at(rest, t);
    if (degenerate(e))
      throw std::invalid_argument(
          "corner angle: a zero-length boundary edge at corner (pattern vertex " +
          std::to_string(t[1]) + ")");
    reference_.push_back(turning_angle(e));
  }
}

double CornerAngleRegularizer::value(const DesignState& state) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  double total = 0.0;
  for (std::size_t c = 0; c < triples_.size(); ++c) {
    const CornerEdges e = edges_at(state.rest, triples_[c]);
    if (degenerate(e)) return std::numeric_limits<double>::infinity();
    const double d = angle_difference(turning_angle(e), reference_[c]);
    total += d * d;
  }
  return total;
}

void CornerAngleRegularizer::add_gradient(const DesignState& state, VecX& /*d_x*/,
                                          VecX& d_rest) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  check_rest_gradient_size(name(), d_rest, num_pattern_);
  for (std::size_t c = 0; c < triples_.size(); ++c) {
    const std::array<int, 3>& t = triples_[c];
    const CornerEdges e = edges_at(state.rest, t);
    if (degenerate(e))
      throw SolverError("corner angle: a boundary edge at pattern vertex " + std::to_string(t[1]) +
                        " has zero length");
    const double d = angle_difference(turning_angle(e), reference_[c]);
    // θ = atan2(c, s), c = in × out, s = in · out: dθ = (s dc − c ds) / (c² + s²).
    const double cr = cross2(e.in, e.out), dot = e.in.dot(e.out);
    const double scale = 2.0 * d / (cr * cr + dot * dot);
    const Vec2 dcr_in(e.out.y(), -e.out.x()), dcr_out(-e.in.y(), e.in.x());
    const Vec2 g_in = scale * (dot * dcr_in - cr * e.out);
    const Vec2 g_out = scale * (dot * dcr_out - cr * e.in);
    d_rest.segment<2>(2 * t[0]) -= g_in;
    d_rest.segment<2>(2 * t[1]) += g_in - g_out;
    d_rest.segment<2>(2 * t[2]) += g_out;
  }
}

}  // namespace tightfit
