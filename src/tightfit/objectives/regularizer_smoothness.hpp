#pragma once
/// Boundary smoothness regularizer on the pattern rest positions (paper Sec. 4.1), the
/// discrete bending energy of Bergou et al. 2008 on each boundary loop:
///   R = Σ_{(i,j) ∈ B} κ_ij² / (‖e_i‖ + ‖e_j‖)       (1/m)
///   κ_ij = 2 (e_i × e_j) / (‖e_i‖‖e_j‖ + e_i·e_j) = 2 tan(θ/2)
/// with e_i, e_j the incoming and outgoing boundary edges of a loop vertex, θ the turning
/// angle there and e_i × e_j the 2D cross product. B holds every boundary-loop vertex
/// except the piece's corners (PatternPiece::corners), where sharp turns are wanted.
/// The weight 1/(‖e_i‖+‖e_j‖) is evaluated at the current (not the initial) lengths, as
/// in the paper. Independent of the garment positions x.
///
/// A boundary that folds back on itself (θ = π, e_i·e_j = −‖e_i‖‖e_j‖) has κ = ∞:
/// value() returns +infinity there (a line search rejects the step) and add_gradient()
/// throws SolverError.
#include <array>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit {

class BoundarySmoothnessRegularizer : public DesignTerm {
 public:
  /// Vertex triples (previous, vertex, next) of all boundary loops without corners.
  explicit BoundarySmoothnessRegularizer(const Garment& garment);

  std::string name() const override { return "boundary smoothness"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return false; }

  /// Global pattern vertices (previous, vertex, next) of every penalized boundary vertex.
  const std::vector<std::array<int, 3>>& triples() const { return triples_; }

 private:
  std::vector<std::array<int, 3>> triples_;
  int num_pattern_ = 0;
};

}  // namespace tightfit
