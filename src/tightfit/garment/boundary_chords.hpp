#pragma once
/// Boundary chords of a meshed pattern piece: interior edges whose two end vertices both
/// lie on the piece's boundary. Welding two pieces along a seam joins their boundary
/// vertices; when both pieces have a chord between the same two seam vertices, the welded
/// garment has an edge with more than two faces (the two chords' triangles close a
/// pocket). Splitting every chord at its midpoint leaves each interior edge with at least
/// one interior end, so that no weld can join two of them.
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit {

/// Splits every interior edge of `mesh` whose two ends are boundary vertices (the first
/// `num_boundary` vertices) at its midpoint: the two triangles on it become four, the
/// midpoint is appended as a new interior vertex. Orientation is kept. Returns how many
/// edges were split. Deterministic (edges in ascending vertex order).
int split_boundary_chords(PieceMesh& mesh, int num_boundary);

}  // namespace tightfit
