#include "tightfit/objectives/directional_stretch_objective.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

const std::string kSource = "directional stretch objective";

/// The element's F, B = Dm⁻¹ and rest area.
struct Kinematics {
  Mat32 f;
  Mat2 b;
  double area = 0.0;
};

Kinematics kinematics(const DesignState& s, const Triangles& tri,
                      const std::vector<int>& to_garment, Eigen::Index e) {
  Mat2 dm;
  Mat32 ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = (s.rest.row(tri(e, k + 1)) - s.rest.row(tri(e, 0))).transpose();
    ds.col(k) =
        s.x.segment<3>(3 * to_garment[tri(e, k + 1)]) - s.x.segment<3>(3 * to_garment[tri(e, 0)]);
  }
  const double det = dm.determinant();
  if (!(std::abs(det) > 1e-14 * dm.squaredNorm()))
    throw SolverError(kSource + ": rest triangle " + std::to_string(e) + " is degenerate");
  Kinematics k;
  k.b = dm.inverse();
  k.f = ds * k.b;
  k.area = 0.5 * std::abs(det);
  return k;
}

}  // namespace

DirectionalStretchObjective::DirectionalStretchObjective(const Garment& garment,
                                                         FabricDirection direction,
                                                         StretchBounds bounds)
    : triangles_(garment.pattern_triangles),
      pattern_to_garment_(garment.pattern_to_garment),
      num_garment_(garment.num_garment_vertices),
      num_pattern_(garment.num_pattern_vertices()) {
  if (!(bounds.min_stretch > 0.0) || !(bounds.max_stretch >= bounds.min_stretch) ||
      !std::isfinite(bounds.min_stretch))
    throw InputError(kSource, "stretch bounds must satisfy 0 < min <= max (got " +
                                  std::to_string(bounds.min_stretch) + ", " +
                                  std::to_string(bounds.max_stretch) + ")");
  c_min_ = bounds.min_stretch * bounds.min_stretch;
  c_max_ = bounds.max_stretch * bounds.max_stretch;  // +inf stays +inf
  std::vector<Vec2> piece_direction;
  for (const PatternPiece& piece : garment.pattern.pieces) {
    const double len = piece.grain.norm();
    if (!(len > 0.0) || !std::isfinite(len))
      throw InputError(kSource, "piece '" + piece.name + "' has no valid grain direction");
    const Vec2 g = piece.grain / len;
    piece_direction.push_back(direction == FabricDirection::along_grain ? g : Vec2(g.y(), -g.x()));
  }
  directions_.reserve(static_cast<size_t>(triangles_.rows()));
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e)
    directions_.push_back(
        piece_direction.at(static_cast<size_t>(garment.triangle_piece.at(static_cast<size_t>(e)))));
}

void DirectionalStretchObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument(kSource + ": state has " + std::to_string(state.x.size()) +
                                " position entries and " + std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

std::vector<double> DirectionalStretchObjective::stretches(const DesignState& state) const {
  check(state);
  std::vector<double> out(static_cast<size_t>(triangles_.rows()));
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const Kinematics k = kinematics(state, triangles_, pattern_to_garment_, e);
    out[static_cast<size_t>(e)] = (k.f * directions_[static_cast<size_t>(e)]).norm();
  }
  return out;
}

double DirectionalStretchObjective::value(const DesignState& state) const {
  check(state);
  double total = 0.0;
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const Kinematics k = kinematics(state, triangles_, pattern_to_garment_, e);
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
    throw std::invalid_argument(kSource + ": gradient vectors have the wrong size");
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    const Kinematics k = kinematics(state, triangles_, pattern_to_garment_, e);
    const Vec2& d = directions_[static_cast<size_t>(e)];
    const Vec3 fd = k.f * d;
    const double c = fd.squaredNorm();
    const double bound = c < c_min_ ? c_min_ : (c > c_max_ ? c_max_ : c);
    if (bound == c) continue;
    const double pen = (c - bound) * (c - bound);
    const double dpen = 2.0 * (c - bound);
    // T_e = A pen(c), c = dᵀFᵀF d: ∂T_e/∂F = 2 A pen'(c) F d dᵀ.
    const Mat32 p = 2.0 * k.area * dpen * fd * d.transpose();
    // F = Ds B: ∂/∂Ds = P Bᵀ; ∂/∂Dm = −Fᵀ P Bᵀ (through F) + pen A Bᵀ (through A).
    const Mat32 g_ds = p * k.b.transpose();
    const Mat2 g_dm = -k.f.transpose() * p * k.b.transpose() + pen * k.area * k.b.transpose();
    const int g0 = pattern_to_garment_[triangles_(e, 0)];
    const int p0 = triangles_(e, 0);
    for (int j = 0; j < 2; ++j) {
      const int gj = pattern_to_garment_[triangles_(e, j + 1)];
      const int pj = triangles_(e, j + 1);
      d_x.segment<3>(3 * gj) += g_ds.col(j);
      d_x.segment<3>(3 * g0) -= g_ds.col(j);
      d_rest.segment<2>(2 * pj) += g_dm.col(j);
      d_rest.segment<2>(2 * p0) -= g_dm.col(j);
    }
  }
}

}  // namespace tightfit
