#include "tightfit/objectives/rest_term_checks.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tightfit {

void check_rest_rows(std::string_view term, const Points2& rest, int num_pattern) {
  if (rest.rows() != num_pattern)
    throw std::invalid_argument(std::string(term) + ": expected " + std::to_string(num_pattern) +
                                " rest positions, got " + std::to_string(rest.rows()));
}

void check_rest_gradient_size(std::string_view term, const VecX& d_rest, int num_pattern) {
  if (d_rest.size() != 2 * static_cast<Eigen::Index>(num_pattern))
    throw std::invalid_argument(std::string(term) + ": rest gradient has the wrong size");
}

std::vector<std::array<int, 3>> boundary_triples(const Garment& garment, BoundaryVertices which) {
  std::vector<std::array<int, 3>> triples;
  for (std::size_t k = 0; k < garment.pattern.pieces.size(); ++k) {
    const PatternPiece& piece = garment.pattern.pieces[k];
    const int o = garment.topology->piece_offset[k];
    for (const std::vector<int>& loop : piece.loops()) {
      const std::size_t n = loop.size();
      if (n < 3) continue;
      for (std::size_t i = 0; i < n; ++i) {
        const bool corner =
            std::find(piece.corners.begin(), piece.corners.end(), loop[i]) != piece.corners.end();
        if (corner != (which == BoundaryVertices::kCorners)) continue;
        triples.push_back({o + loop[(i + n - 1) % n], o + loop[i], o + loop[(i + 1) % n]});
      }
    }
  }
  return triples;
}

}  // namespace tightfit
