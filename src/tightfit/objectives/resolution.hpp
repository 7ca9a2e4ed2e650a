#pragma once
/// Mesh-resolution weights that make the design terms measure the same thing on any
/// mesh of the same fit, so that remeshing a pattern during optimization does not change
/// the objective (paper Sec. 4's sums run over vertices and edges, whose number a
/// remeshing changes).
///
/// A term that sums a per-vertex or per-edge quantity is weighted as a quadrature of the
/// integral it stands for: a vertex's weight is its share of the garment's rest area
/// (m²), a boundary vertex's or edge's its share of the boundary's rest length (m), each
/// divided by the same share of a REFERENCE mesh, the design's initial one. On the
/// reference mesh the weights are about 1 (exactly 1 on average), so a term's value and
/// the weights a scene gives it keep their meaning; on a coarser remeshed pattern each
/// vertex weighs more, on a finer one less, and the sum stays the same integral.
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/garment.hpp"

namespace tightfit {

/// The resolution of a reference mesh: what one vertex or boundary edge stands for.
struct ResolutionReference {
  double vertex_area = 0.0;    ///< mean rest area per garment vertex (m²)
  double boundary_edge = 0.0;  ///< mean rest length of a boundary edge (m)
  /// Whether it was set (a default-constructed reference means "the mesh's own").
  bool known() const { return vertex_area > 0.0 && boundary_edge > 0.0; }
};

/// The resolution of `garment`'s rest pattern: its total rest area over its number of
/// garment vertices, and the mean rest length of its pieces' boundary edges.
ResolutionReference resolution_of(const Garment& garment);

/// `reference` when known, else the resolution of `garment`.
ResolutionReference resolution_or_own(const ResolutionReference& reference, const Garment& garment);

/// Per garment vertex: one third of the rest area of every pattern triangle around it
/// (m²; a seam vertex collects from both pieces). Sums to the garment's rest area.
VecX garment_vertex_areas(const Garment& garment);

/// Per garment vertex: half the rest length of every edge of a pinned boundary that ends
/// there (m; 0 for a vertex on no pinned boundary).
VecX pinned_vertex_lengths(const Garment& garment);

}  // namespace tightfit
