#pragma once
/// Corner-angle regularizer on the pattern rest positions: keeps every corner of every
/// piece (PatternPiece::corners: seam ends, pin ends, sharp turns of the outline) at the
/// angle it has in the reference pattern,
///   R = Σ_c (θ_c − θ_c⁰)²        (rad²)
/// with θ_c the turning angle of the boundary loop at corner c (atan2 of the cross and
/// dot products of the incoming and outgoing boundary edges; the interior angle is
/// π − θ_c) and θ_c⁰ its value at construction. The boundary-smoothness regularizer
/// leaves corners out, so without this term nothing stops a corner from drawing out
/// into a spike (the optimized pants' front crotch point went from 89° to 51° while the
/// back one opened to 137°). Pattern makers square the corners where seams meet a hem,
/// a waistline or another seam so that the sewn line runs on smoothly; the layout's
/// flattening gives those angles (it is conformal), and this term holds them.
///
/// The reference is the pattern the term is built from: the design's initial pattern,
/// and after a remeshing the remeshed one (like every reference of DesignProblem).
/// Independent of the garment positions x. A corner whose edges have zero length has no
/// angle: value() returns +infinity there (a line search rejects the step) and
/// add_gradient() throws SolverError.
#include <array>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit {

class CornerAngleRegularizer : public DesignTerm {
 public:
  /// The corners of every piece's boundary loops, with their angles in `garment`'s rest
  /// pattern as the reference.
  explicit CornerAngleRegularizer(const Garment& garment);

  std::string name() const override { return "corner angle"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return false; }

  /// Global pattern vertices (previous, corner, next) of every corner.
  const std::vector<std::array<int, 3>>& triples() const { return triples_; }
  /// Reference turning angle (rad) of each corner, in triples() order.
  const std::vector<double>& reference_angles() const { return reference_; }

 private:
  std::vector<std::array<int, 3>> triples_;
  std::vector<double> reference_;
  int num_pattern_ = 0;
};

}  // namespace tightfit
