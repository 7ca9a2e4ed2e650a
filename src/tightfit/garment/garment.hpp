#pragma once
/// A garment ready to simulate: its pattern (flat pieces with their rest positions,
/// seams, pinned boundaries), its connectivity (GarmentTopology: the welding of seam
/// vertices into shared 3D garment vertices, triangles, seam edges, pinned vertices;
/// shared and never changed) and the embedding of every garment vertex on the body's
/// Loop limit surface.
///
/// Geometry lives in the pattern pieces: each pattern vertex keeps its own 2D rest
/// position in its piece (Xbar of the paper); the 3D position of garment vertex i is the
/// limit-surface point embedding[i]. Indexing: garment_topology.hpp.
///
/// Made by build_garment (garment_builder.hpp) from a body and a layout spec, or by
/// weld_pattern from a pattern plus an embedding computed elsewhere.
#include <memory>
#include <vector>

#include "tightfit/garment/garment_topology.hpp"
#include "tightfit/garment/pattern.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit {

struct Garment {
  Pattern pattern;
  /// The connectivity of `pattern`'s mesh (never null in a welded garment).
  std::shared_ptr<const GarmentTopology> topology;
  std::vector<SurfacePoint> embedding;  ///< per garment vertex: where it lies on the limit surface

  int num_pattern_vertices() const { return topology ? topology->num_pattern_vertices() : 0; }
  int num_garment_vertices() const { return topology ? topology->num_garment_vertices : 0; }
  /// Stacked rest positions of all pattern vertices (num_pattern_vertices × 2, m).
  Points2 rest_positions() const;
  /// Writes stacked rest positions back into the pieces.
  void set_rest_positions(const Points2& rest);
  /// Holds exactly `pinned` (garment vertices) instead of the pattern's pinned
  /// boundaries: a new topology, the rest shared. Throws InputError for a vertex out of
  /// range.
  void set_pinned_vertices(std::vector<int> pinned);
};

/// The garment of `pattern` welded by its seams (weld_topology). The embedding is left
/// empty. Throws InputError (source "pattern") as weld_topology does.
Garment weld_pattern(Pattern pattern);

}  // namespace tightfit
