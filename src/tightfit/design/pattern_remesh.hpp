#pragma once
/// Remeshing of degraded pattern pieces during optimization.
///
/// As the optimizer moves the boundary points, the biharmonic coordinates drag the
/// interior along and triangles can degrade (small angles, tiny or inverted elements).
/// remesh_garment then replaces the meshes of the chosen pieces:
///  1. Boundary (remesh_boundary.hpp, remesh_piece.hpp; the arc-length sampling and edge
///     counts of garment/boundary_resampling.hpp, as the pattern builder's): every piece's
///     boundary loop is cut into units at its break points
///     (corners, ends of seam sides and of open pinned boundaries). A free unit of a
///     remeshed piece is resampled at `edge_length` by even 2D arc length. A seam is
///     resampled as a whole in the seam's own index space (side vertex i of a meets
///     side vertex i of b), split where either side has a break point: each sub-range
///     gets n = round(mean 2D length of the two sides / edge_length) edges, sampled at
///     the fractions k/n of the 3D arc length of the WELDED seam polyline, which is the
///     same curve for both sides. Both sides therefore keep equal vertex counts, and new
///     vertex k of side a and of side b lie at the same old seam edge and parameter:
///     they weld to one 3D point. A seam is resampled when either of its pieces is
///     remeshed, so a piece sewn to a remeshed one is remeshed too (only its seam with
///     the remeshed piece is resampled; its other units keep their vertices).
///     Break-point vertices are old vertices and stay exactly where they were. The rim of
///     a hole (opening) is resampled at `edge_length` by even 2D arc length from its
///     old first vertex.
///  2. Interior: the new boundary polygon is meshed in 2D by mesh_piece at
///     `edge_length` (garment/piece_mesher.hpp, as the layout builder does).
///  3. Embedding transfer (EmbeddingTransfer, embedding_transfer.hpp): each new vertex's 3D point
///  is
///     interpolated in the old rest mesh from the old equilibrium positions (linearly
///     along the old boundary edge for boundary samples, barycentrically in the old
///     triangle containing it for interior ones) and projected onto the body's limit
///     surface (Newton from the nearest old vertex's surface point). A new vertex that
///     coincides with an old vertex gets the old vertex's surface point exactly.
///  4. The new pattern is welded (weld_pattern) and every garment vertex gets the
///     transferred point of its first pattern vertex. Pieces not remeshed keep their
///     vertices, triangles and surface points unchanged.
#include <string>
#include <vector>

#include "tightfit/design/embedding_transfer.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// When a piece counts as degraded and how it is remeshed (scene "optimize"/"remesh").
struct PatternRemeshOptions {
  bool enabled = true;
  /// A piece is degraded when its smallest rest-triangle angle falls below this
  /// (degrees) ...
  double min_angle_deg = 10.0;
  /// ... or a rest triangle's area falls below this fraction of the area of an
  /// equilateral triangle of the piece's target edge length, or a triangle is inverted.
  double min_area_fraction = 0.1;
  /// Target edge length of the new meshes (m); 0: per piece, the mean rest edge length
  /// of its mesh when the optimization started.
  double edge_length = 0.0;
  /// Optimal-Delaunay smoothing steps of the mesher (mesh_piece).
  int smoothing_iterations = 10;
};

/// Shape quality of one piece's rest mesh.
struct PieceQuality {
  /// Smallest interior angle (degrees; 0 when inverted), leaving out the angles at sharp
  /// corners of the outline (boundary vertices whose triangles' angles sum below 60°):
  /// the corner bounds them and no remeshing can raise them.
  double min_angle_deg = 0.0;
  double min_area = 0.0;  ///< smallest signed area (m²; <= 0: an inverted triangle)
};

/// Quality of `piece` at its current rest positions.
PieceQuality piece_quality(const PatternPiece& piece);

/// Mean rest edge length of a piece's triangles (m).
double mean_edge_length(const PatternPiece& piece);

struct PatternRemeshResult {
  Garment garment;            ///< the new garment, welded, with its embedding
  EmbeddedState state;        ///< transferred garment points, the old body positions
  std::vector<int> remeshed;  ///< pieces whose mesh changed (sorted)
  /// Per new piece: the old piece is kept unchanged (same vertices and triangles).
  std::vector<bool> unchanged;
};

/// Remeshes `pieces` (indices into old_garment.pattern.pieces) and the pieces sewn to
/// them, as described in the header comment. `edge_length` holds the target edge
/// length (m) of every piece; `smoothing_iterations` goes to mesh_piece. Throws
/// InputError (source "pattern piece NAME") when a seam side or pinned boundary is not
/// a run of consecutive boundary vertices, or a new boundary cannot be meshed.
PatternRemeshResult remesh_garment(const Garment& old_garment, const EmbeddedState& state,
                                   const Points3& positions, const LimitSurface& surface,
                                   const std::vector<int>& pieces,
                                   const std::vector<double>& edge_length,
                                   int smoothing_iterations);

}  // namespace tightfit
