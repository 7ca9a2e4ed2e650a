#pragma once
/// Finiteness of what the optimizer accepts: an equilibrium (garment surface points and
/// deformed body) or a pattern's rest positions. A NaN or infinity there is never
/// accepted (DesignProblem rejects such an evaluation; a remeshing that produces one is
/// a SolverError, see optimization_problem.hpp).
#include <string>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"

namespace tightfit {

/// Where the first non-finite number of `state` is — "garment surface point 12 (u, v)"
/// or "body vertex 3" — or an empty string when every number is finite.
std::string non_finite_place(const EmbeddedState& state);

/// Where the first non-finite rest position of `pattern` is — "piece 'front', vertex
/// 7" — or an empty string when every rest position is finite.
std::string non_finite_place(const Pattern& pattern);

}  // namespace tightfit
