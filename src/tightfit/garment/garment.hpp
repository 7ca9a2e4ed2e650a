#pragma once
/// A garment ready to simulate: its pattern (flat pieces, seams, pinned boundaries),
/// the welding of seam vertices into shared 3D garment vertices, and the embedding of
/// every garment vertex on the body's Loop limit surface.
///
/// Indexing. Pattern vertices are numbered globally, piece after piece
/// (`piece_offset[k] + local index`); garment vertices are the welded 3D vertices: the
/// two sides of a seam share one garment vertex per seam vertex pair, and seam ends
/// where several pieces meet (a crotch point) are one garment vertex for all of them.
/// Each pattern vertex keeps its own 2D rest position in its piece (Xbar of the paper);
/// the 3D position of garment vertex i is the limit-surface point embedding[i].
///
/// Made by build_garment (garment_builder.hpp) from a body and a layout spec, or by
/// weld_pattern from a pattern plus an embedding computed elsewhere.
#include <array>
#include <vector>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit {

struct Garment {
  Pattern pattern;
  std::vector<int>
      piece_offset;  ///< first global pattern vertex of each piece (+ total at the end)
  std::vector<int> pattern_to_garment;  ///< global pattern vertex → garment vertex
  int num_garment_vertices = 0;
  Triangles pattern_triangles;          ///< all pieces' triangles in global pattern-vertex indices
  Triangles garment_triangles;          ///< the same triangles in garment-vertex indices
  std::vector<int> triangle_piece;      ///< piece of each triangle
  std::vector<SurfacePoint> embedding;  ///< per garment vertex: where it lies on the limit surface
  std::vector<int> pinned;  ///< garment vertices held at their embedding (sorted, unique)

  int num_pattern_vertices() const { return piece_offset.empty() ? 0 : piece_offset.back(); }
  /// Stacked rest positions of all pattern vertices (num_pattern_vertices × 2, m).
  Points2 rest_positions() const;
  /// Writes stacked rest positions back into the pieces.
  void set_rest_positions(const Points2& rest);
  /// Seam edges as global pattern-vertex pairs, one per seam edge per side (Eq. 12).
  std::vector<std::array<int, 2>> seam_edges() const;
};

/// Numbers the pattern vertices, welds seam vertex pairs into garment vertices
/// (transitively, so seams meeting at a corner share one vertex), and collects pinned
/// vertices. The embedding is left empty. Throws InputError (source "pattern") when a
/// seam's sides differ in vertex count or name an invalid piece or vertex.
Garment weld_pattern(Pattern pattern);

}  // namespace tightfit
