#include "tightfit/objectives/directional_stretch_objective.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/objectives/element_kinematics.hpp"

namespace tightfit {
namespace {

const std::string kDirectionalSource = "directional stretch objective";

ElementKinematics directional_kinematics(const DesignState& s, const Triangles& tri,
                                         const std::vector<int>& to_garment, Eigen::Index e) {
  return element_kinematics(s, tri, to_garment, e, kDirectionalSource);
}

}  // namespace

DirectionalStretchObjective::DirectionalStretchObjective(const Garment& garment,
                                                         FabricDirection direction,
                                                         StretchBounds bounds)
    : triangles_(garment.topology->pattern_triangles),
      pattern_to_garment_(garment.topology->pattern_to_garment),
      num_garment_(garment.num_garment_vertices()),
      num_pattern_(garment.num_pattern_vertices()) {
  if (!(bounds.min_stretch > 0.0) || !(bounds.max_stretch >= bounds.min_stretch) ||
      !std::isfinite(bounds.min_stretch))
    throw InputError(kDirectionalSource, "stretch bounds must satisfy 0 < min <= max (got " +
                                             std::to_string(bounds.min_stretch) + ", " +
                                             std::to_string(bounds.max_stretch) + ")");
  c_min_ = bounds.min_stretch * bounds.min_stretch;
  c_max_ = bounds.max_stretch * bounds.max_stretch;  // +inf stays +inf
  std::vector<Vec2> piece_direction;
  for (const PatternPiece& piece : garment.pattern.pieces) {
    const double len = piece.grain.norm();
    if (!(len > 0.0) || !std::isfinite(len))
      throw InputError(kDirectionalSource,
                       "piece '" + piece.name + "' has no valid grain direction");
    const Vec2 g = piece.grain / len;
    piece_direction.push_back(direction == FabricDirection::kAlongGrain ? g : Vec2(g.y(), -g.x()));
  }
  directions_.reserve(static_cast<size_t>(triangles_.rows()));
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e)
    directions_.push_back(piece_direction.at(
        static_cast<size_t>(garment.topology->triangle_piece.at(static_cast<size_t>(e)))));
}

void DirectionalStretchObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument(kDirectionalSource + ": state has " +
                                std::to_string(state.x.size()) + " position entries and " +
                                std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

std::vector<double> DirectionalStretchObjective::stretches(const DesignState& state) const {
  check(state);
  std::vector<double> out(static_cast<size_t>(triangles_.rows()));
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const ElementKinematics k = directional_kinematics(state, triangles_, pattern_to_garment_, e);
    out[static_cast<size_t>(e)] = (k.f * directions_[static_cast<size_t>(e)]).norm();
  }
  return out;
}

double DirectionalStretchObjective::value(const DesignState& state) const {
  check(state);
  double total = 0.0;
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const ElementKinematics k = directional_kinematics(state, triangles_, pattern_to_garment_, e);
    const double c = (k.f * directions_[static_cast<size_t>(e)]).squaredNorm();
    if (c < c_min_) total += k.area * (c - c_min_) * (c - c_min_);
    if (c > c_max_) total += k.area * (c - c_max_) * (c - c_max_);
  }
  return total;
}

void DirectionalStretchObjective::add_gradient(const DesignState& state, VecX& d_x,
                                               VecX& d_rest) const {
  check(state);
  if (d_x.size() != state.x.size() || d_rest.size() != 2 * state.rest.rows())
    throw std::invalid_argument(kDirectionalSource + ": gradient vectors have the wrong size");
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const ElementKinematics k = directional_kinematics(state, triangles_, pattern_to_garment_, e);
    const Vec2& d = directions_[static_cast<size_t>(e)];
    const Vec3 fd = k.f * d;
    const double c = fd.squaredNorm();
    const double bound = c < c_min_ ? c_min_ : (c > c_max_ ? c_max_ : c);
    if (bound == c) continue;
    const double pen = (c - bound) * (c - bound);
    const double dpen = 2.0 * (c - bound);
    // T_e = A pen(c), c = dᵀFᵀF d: ∂T_e/∂F = 2 A pen'(c) F d dᵀ.
    const Mat32 p = 2.0 * k.area * dpen * fd * d.transpose();
    add_element_gradient(k, p, pen, triangles_, pattern_to_garment_, e, d_x, d_rest);
  }
}

}  // namespace tightfit
