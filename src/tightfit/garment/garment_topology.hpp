#pragma once
/// The connectivity of a welded garment, apart from its geometry (geometry-central's
/// split): how pattern vertices are numbered, which of them a seam welds into one garment
/// vertex, the triangles in both numberings, the seam edges and the pinned vertices.
/// Built once per pattern mesh by weld_topology (or weld_pattern, garment.hpp) and never
/// changed afterwards: the garment, its energies and its design terms share one
/// instance (`std::shared_ptr<const GarmentTopology>`). A design step moves rest
/// positions and embeddings only; a remesh builds a new topology.
///
/// Indexing. Pattern vertices are numbered globally, piece after piece
/// (`piece_offset[k] + local index`); garment vertices are the welded 3D vertices: the
/// two sides of a seam share one garment vertex per seam vertex pair, and seam ends
/// where several pieces meet (a crotch point) are one garment vertex for all of them.
#include <array>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/pattern.hpp"

namespace tightfit {

struct GarmentTopology {
  /// First global pattern vertex of each piece, and the total at the end (pieces + 1).
  std::vector<int> piece_offset;
  /// Global pattern vertex → garment vertex (num_pattern_vertices entries).
  std::vector<int> pattern_to_garment;
  int num_garment_vertices = 0;
  /// All pieces' triangles in global pattern-vertex indices (m×3, counter-clockwise in
  /// each piece's plane).
  Triangles pattern_triangles;
  /// The same triangles in garment-vertex indices (the 3D garment mesh).
  Triangles garment_triangles;
  /// Piece of each triangle (m entries).
  std::vector<int> triangle_piece;
  /// Seam edges as global pattern-vertex pairs, one per seam edge per side (Eq. 12).
  std::vector<std::array<int, 2>> seam_edges;
  /// Garment vertices held at their embedding (sorted, unique).
  std::vector<int> pinned;

  int num_pattern_vertices() const { return piece_offset.empty() ? 0 : piece_offset.back(); }
  int num_triangles() const { return static_cast<int>(pattern_triangles.rows()); }
  /// The piece a global pattern vertex belongs to.
  int piece_of(int pattern_vertex) const;
};

/// Consecutive vertex pairs of each polyline: the seam edges of seam sides given as
/// pattern-vertex polylines.
std::vector<std::array<int, 2>> polyline_edges(const std::vector<std::vector<int>>& polylines);

/// Numbers the pattern vertices, welds seam vertex pairs into garment vertices
/// (transitively, so seams meeting at a corner share one vertex) and collects the seam
/// edges and pinned vertices. Throws InputError (source "pattern") when a seam's sides
/// differ in vertex count or name an invalid piece or vertex, a triangle has a vertex out
/// of range, a pinned boundary names an invalid piece or vertex, or the welded triangles
/// are no surface (two corners of a triangle welded together, an edge with more than two
/// triangles: pieces joined along the same pair of seam vertices by more than their seam).
GarmentTopology weld_topology(const Pattern& pattern);

/// The topology of `pattern` with pattern vertices welded by an explicit map instead of
/// by its seams (`pattern_to_garment`: one garment vertex in [0, num_garment_vertices)
/// per global pattern vertex). Throws InputError (source "pattern") for a map of the
/// wrong size or out of range, and for the errors of weld_topology.
GarmentTopology weld_topology(const Pattern& pattern, std::vector<int> pattern_to_garment,
                              int num_garment_vertices);

/// The topology of one piece given as raw arrays, for energies built without a Pattern
/// (tests, benchmarks): `num_pattern_vertices` pattern vertices welded by
/// `pattern_to_garment` (one garment vertex in [0, num_garment_vertices) each), the
/// piece's `triangles` and `seam_edges` in pattern-vertex indices, nothing pinned.
/// Throws InputError naming `source` for a map of the wrong size or out of range and for
/// a triangle or seam edge with a vertex out of range.
GarmentTopology one_piece_topology(const std::string& source, Eigen::Index num_pattern_vertices,
                                   Triangles triangles, std::vector<std::array<int, 2>> seam_edges,
                                   std::vector<int> pattern_to_garment, int num_garment_vertices);

}  // namespace tightfit
