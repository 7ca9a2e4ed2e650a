#include "tightfit/design/finite_state.hpp"

#include <cmath>

namespace tightfit {

std::string non_finite_place(const EmbeddedState& state) {
  for (std::size_t i = 0; i < state.garment.size(); ++i)
    if (!std::isfinite(state.garment[i].u) || !std::isfinite(state.garment[i].v))
      return "garment surface point " + std::to_string(i) + " (u, v)";
  for (Eigen::Index i = 0; i < state.body.rows(); ++i)
    if (!state.body.row(i).allFinite()) return "body vertex " + std::to_string(i);
  return {};
}

std::string non_finite_place(const Pattern& pattern) {
  for (const PatternPiece& piece : pattern.pieces)
    for (Eigen::Index i = 0; i < piece.rest.rows(); ++i)
      if (!piece.rest.row(i).allFinite())
        return "piece '" + piece.name + "', vertex " + std::to_string(i);
  return {};
}

}  // namespace tightfit
