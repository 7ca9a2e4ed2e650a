#pragma once
/// The L-BFGS two-loop recursion and its memory of curvature pairs (Nocedal & Wright,
/// Algorithm 7.4), as PatternOptimizer uses them.
#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

/// d = −H g over the pairs of `memory` (initial scaling γ = sᵀy / yᵀy of the newest pair);
/// −g when the memory is empty.
VecX lbfgs_direction(const LbfgsMemory& memory, const VecX& g);

/// Appends the pair (s, y) when sᵀy > 1e-12 ‖s‖‖y‖ (curvature condition; no Wolfe test
/// is made), dropping the oldest beyond `capacity` pairs. Returns whether it was kept.
bool lbfgs_push(LbfgsMemory& memory, const VecX& s, const VecX& y, int capacity);

/// Drops the oldest pairs beyond `capacity`.
void lbfgs_trim(LbfgsMemory& memory, int capacity);

/// Largest 2D move of one parameter point (x, y pairs) for a step d (m).
double max_point_move(const VecX& d);

}  // namespace tightfit
