#pragma once
/// Directional stretch objective: the stretch & compression penalty of paper Eq. 30
/// applied to the stretch of the fabric along one material direction per piece instead
/// of to the principal stretches. For a pants leg cut with the grain along the leg,
/// "30 % circumferential stretch" is the stretch ACROSS the grain (the weft).
///
///   T = Σ_e A_e pen(c_e),   c_e = d_eᵀ C_e d_e = ‖F_e d_e‖²,
///   pen(c) = (c − c_min)² for c < c_min,  (c − c_max)² for c > c_max,  0 in between,
/// with F_e = Ds Dm⁻¹ as in ClothEnergy, C_e = F_eᵀF_e, A_e the rest area (m²) and d_e
/// the unit rest-space direction of the element's piece: its grain line
/// (PatternPiece::grain) or the grain turned by −90° (across the grain). The direction is
/// fixed in piece coordinates (it is the fabric's weave), so it does not turn when the
/// optimizer reshapes a piece. c_e is a SQUARED stretch like the eigenvalues of Eq. 30;
/// bounds are given as stretches s (1.3 = 30 %), c_min = s_min², c_max = s_max². T is in
/// m². pen is C¹, so T is C¹ in x and Xbar; depends on both.
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/stretch_objective.hpp"

namespace tightfit {

/// Which fabric direction of each piece the objective measures.
enum class FabricDirection {
  kAlongGrain,   ///< PatternPiece::grain
  kAcrossGrain,  ///< the grain turned by −90° in the piece plane (the weft)
};

class DirectionalStretchObjective : public DesignTerm {
 public:
  /// Over all cloth triangles of the garment. Throws InputError (source "directional
  /// stretch objective") unless 0 < s_min <= s_max (s_max may be +infinity), and when a
  /// piece's grain is not a finite non-zero vector.
  DirectionalStretchObjective(const Garment& garment, FabricDirection direction,
                              StretchBounds bounds);

  std::string name() const override { return "directional stretch"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }

  /// The stretch ‖F_e d_e‖ (not squared) of every element at the state, for reports/tests.
  std::vector<double> stretches(const DesignState& state) const;

  double squared_min() const { return c_min_; }
  double squared_max() const { return c_max_; }

 private:
  void check(const DesignState& state) const;

  Triangles triangles_;           // over pattern vertices
  std::vector<Vec2> directions_;  // unit rest direction per triangle
  std::vector<int> pattern_to_garment_;
  int num_garment_ = 0;
  int num_pattern_ = 0;
  double c_min_ = 1.0;
  double c_max_ = 1.69;
};

}  // namespace tightfit
