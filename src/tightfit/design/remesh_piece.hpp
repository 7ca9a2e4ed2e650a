#pragma once
/// Remeshing step 2 (pattern_remesh.hpp): one piece's new boundary, from its units
/// (remesh_boundary.hpp), and the new mesh inside it.
#include <vector>

#include "tightfit/design/remesh_boundary.hpp"

namespace tightfit {

/// Where a new pattern vertex comes from, in the old piece.
struct VertexSource {
  enum Kind { kOldVertex, kEdge, kRestPoint } kind = kOldVertex;
  int from = -1;  ///< old local vertex (kOldVertex, kEdge)
  int to = -1;    ///< old local vertex (kEdge)
  double t = 0.0;
  Vec2 q = Vec2::Zero();  ///< old rest point (m; kRestPoint)
};

/// A new vertex of a seam side: sample `sample` of SeamResampling::samples of seam
/// `seam`, on side `side` (0: a, 1: b), is new local vertex `vertex`.
struct SeamVertex {
  int seam = -1;
  int side = -1;
  int sample = -1;
  int vertex = -1;
};

/// A remeshed piece.
struct ResampledPiece {
  PatternPiece piece;                     ///< new boundary loop first, then holes, then interior
  std::vector<VertexSource> sources;      ///< per new vertex
  std::vector<int> old_to_new;            ///< per old vertex: the new vertex on it, −1 none
  std::vector<SeamVertex> seam_vertices;  ///< the seam samples it emitted
};

/// Remeshes piece `p` of `pattern`: its seam units take the seam samples of `seams`
/// (resample_seams), its free units are resampled at `edge_length` (m) by even 2D arc
/// length when `resample_free` (else they keep their vertices), each hole rim is
/// resampled at `edge_length` from its first vertex, and mesh_piece meshes the inside
/// with `smoothing_iterations`. Break-point vertices are old vertices at their old
/// places. Throws InputError (source "pattern piece NAME") when the new boundary cannot
/// be meshed.
ResampledPiece remesh_piece(const Pattern& pattern, int p, const BoundaryPlan& plan,
                            const std::vector<SeamResampling>& seams, bool resample_free,
                            double edge_length, int smoothing_iterations);

}  // namespace tightfit
