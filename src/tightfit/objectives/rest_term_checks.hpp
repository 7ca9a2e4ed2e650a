#pragma once
/// Size checks shared by the design terms of the rest pattern alone (the regularizers):
/// each throws std::invalid_argument naming the term.
#include <array>
#include <string_view>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/garment.hpp"

namespace tightfit {

/// `rest` must have `num_pattern` rows (one 2D rest position per pattern vertex).
void check_rest_rows(std::string_view term, const Points2& rest, int num_pattern);
/// `d_rest` must have 2·`num_pattern` entries.
void check_rest_gradient_size(std::string_view term, const VecX& d_rest, int num_pattern);

/// Which vertices of the pieces' boundary loops boundary_triples() lists.
enum class BoundaryVertices { kCorners, kAllButCorners };

/// Global pattern vertices (previous, vertex, next) of the chosen vertices of every
/// boundary loop (outer and holes, PatternPiece::loops()) of every piece with at least
/// three vertices, piece after piece in loop order; corners are PatternPiece::corners.
std::vector<std::array<int, 3>> boundary_triples(const Garment& garment, BoundaryVertices which);

}  // namespace tightfit
