#pragma once
/// Carries the L-BFGS curvature pairs across a remeshing (PatternOptimizer): every pair
/// (s, y) lives on the design parameters, the 2D positions of the boundary points; after
/// a remeshing the boundary points of a remeshed piece are other points on (nearly) the
/// same outline. Each new point takes the values of the old points of its piece nearest
/// to it (inverse-distance weights over the two nearest; an unchanged point its own).
/// s is a displacement per point and is interpolated as it is; y is a gradient
/// difference, whose per-point entries scale with the length of outline a point stands
/// for, so it is interpolated and scaled by the ratio of the point spacings (new / old).
/// Pairs whose carried curvature sᵀy is no longer positive are dropped.
#include <vector>

#include "tightfit/design/biharmonic_coordinates.hpp"
#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

/// The boundary points of a parametrization: positions (n×2, from p) and the piece of
/// each point.
struct ParameterPoints {
  Points2 positions;
  std::vector<int> piece;
};

/// The piece of every parameter point of `coordinates`.
std::vector<int> parameter_pieces(const BiharmonicCoordinates& coordinates);

/// `p` as points, with the piece of each parameter point (`piece_of_point`).
ParameterPoints parameter_points(const VecX& p, std::vector<int> piece_of_point);

/// The pairs of `memory` (on `from`) carried to the parametrization `to`.
LbfgsMemory transfer_memory(const LbfgsMemory& memory, const ParameterPoints& from,
                            const ParameterPoints& to);

}  // namespace tightfit
