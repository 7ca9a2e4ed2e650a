#pragma once
/// Shape objective (paper Sec. 5.1, Eq. 28 as corrected in docs/design.md §4): how far the
/// garment is from a target surface, measured with the IMLS signed distance f of
/// imls_surface.hpp (with its documented fallback far from the target):
///   T_shape = Σ_{i ∈ V} w_i f(x_i)²        (m²)
/// over a set V of garment vertices (all by default), with vertex weights w_i: the
/// vertex's share of the rest area over that of the design's initial mesh
/// (shape_vertex_weights, objectives/resolution.hpp), so that T is the same on any mesh
/// of the same fit — the paper's unweighted sum (w_i = 1) shrinks when a remeshing leaves
/// fewer vertices. Depends on x only.
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/imls_surface.hpp"
#include "tightfit/objectives/resolution.hpp"

namespace tightfit {

class ShapeObjective : public DesignTerm {
 public:
  /// `vertices`: garment vertices in [0, num_garment_vertices) that should lie on the
  /// target; empty means all. `weights`: w_i per garment vertex; empty means 1 each.
  /// Throws std::invalid_argument on an index out of range or weights of the wrong size,
  /// negative or not finite.
  ShapeObjective(ImlsSurface target, int num_garment_vertices, std::vector<int> vertices = {},
                 VecX weights = {});

  std::string name() const override { return "shape"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return true; }

  /// f(x_i) (m) for every vertex of V, in the order of vertices().
  VecX distances(const VecX& x) const;
  const std::vector<int>& vertices() const { return vertices_; }
  const ImlsSurface& target() const { return target_; }

 private:
  void check(const VecX& x) const;

  ImlsSurface target_;
  int num_garment_ = 0;
  std::vector<int> vertices_;
  VecX weights_;
};

/// w_i of every garment vertex of `garment`: its share of the rest area
/// (garment_vertex_areas) over `reference`'s area per vertex (the garment's own when
/// `reference` is not known).
VecX shape_vertex_weights(const Garment& garment, const ResolutionReference& reference);

/// The garment vertices not on a pinned boundary (not in Garment::pinned), ascending:
/// the vertex set of a shape objective that leaves the prescribed boundary places alone.
std::vector<int> unpinned_vertices(const Garment& garment);

}  // namespace tightfit
