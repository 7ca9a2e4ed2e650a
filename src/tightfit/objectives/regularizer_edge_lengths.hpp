#pragma once
/// Edge-length regularizers on the pattern rest positions Xbar (paper Sec. 4.1, Eq. 24):
///   R = Σ_i w_i (‖e_i^1‖ − ‖e_i^2‖)²      (m²)
/// over a fixed list of edge pairs, with w_i a reference boundary edge over the pair's
/// mean rest length at construction (objectives/resolution.hpp: about 1 on the design's
/// initial mesh), so that a seam whose sides differ by the same fraction of their length
/// costs the same on any mesh. Two instances:
///  * seam compatibility: the i-th edge of one side of a seam against the i-th edge of
///    the other side (the sides are sewn vertex by vertex, so equal edges keep the
///    seam lengths equal edge by edge);
///  * even boundary spacing: every two consecutive edges of every boundary loop
///    (also across corners), which keeps boundary vertices from bunching up.
/// Independent of the garment positions x. Smooth while no edge has zero length.
#include <array>
#include <string>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/resolution.hpp"

namespace tightfit {

class EdgeLengthDifferenceTerm : public DesignTerm {
 public:
  /// Two rest edges, each as two global pattern vertices.
  struct EdgePair {
    std::array<int, 2> first;
    std::array<int, 2> second;
    double weight = 1.0;  ///< w_i ≥ 0
  };

  /// `pairs` over global pattern vertices in [0, num_pattern_vertices). Throws
  /// std::invalid_argument on an index out of range.
  EdgeLengthDifferenceTerm(std::string name, std::vector<EdgePair> pairs, int num_pattern_vertices);

  std::string name() const override { return name_; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return false; }

  const std::vector<EdgePair>& pairs() const { return pairs_; }

 private:
  std::string name_;
  std::vector<EdgePair> pairs_;
  int num_pattern_ = 0;
};

/// Seam compatibility (Eq. 24, name "seam length"): for every seam, edge
/// (a_i, a_{i+1}) of side a against edge (b_i, b_{i+1}) of side b.
EdgeLengthDifferenceTerm seam_length_regularizer(const Garment& garment,
                                                 const ResolutionReference& reference = {});

/// Even boundary spacing (Eq. 24 reused, name "boundary spacing"): for every boundary
/// loop and every loop vertex v, its incoming edge against its outgoing edge.
EdgeLengthDifferenceTerm even_spacing_regularizer(const Garment& garment,
                                                  const ResolutionReference& reference = {});

}  // namespace tightfit
