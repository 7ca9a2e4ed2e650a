#pragma once
/// Remeshing step 1 (pattern_remesh.hpp): how the pattern's boundary loops are cut into
/// units at their break points (corners, ends of seam sides and of open pinned
/// boundaries), and how every seam is resampled in its own index space so that both
/// sides keep equal vertex counts.
#include <array>
#include <string>
#include <vector>

#include "tightfit/garment/garment.hpp"

namespace tightfit {

/// A piece's boundary loop with look-ups.
struct BoundaryLoop {
  std::vector<int> vertices;  ///< the boundary loop (local vertex indices)
  std::vector<int> pos;       ///< local vertex → loop position, −1 off the loop
  int size() const { return static_cast<int>(vertices.size()); }
  /// The vertex at loop position k (any integer, taken modulo the loop size).
  int at(int k) const { return vertices[static_cast<size_t>(((k % size()) + size()) % size())]; }
};

/// A seam side (or an open pinned boundary) as a run of its piece's boundary loop.
struct SideRun {
  int piece = -1;
  int dir = 1;                ///< +1: side order = loop order, −1: reversed
  std::vector<int> loop_pos;  ///< loop position of every side vertex
};

/// The run of `loop` that `side` (of `piece`, whose boundary `loop` is) follows. Throws
/// InputError (source "pattern piece NAME", naming `what`) when a side vertex is off the
/// loop or the side is not a run of consecutive loop vertices.
SideRun side_run(const BoundaryLoop& loop, const SeamSide& side, const PatternPiece& piece,
                 const std::string& what);

/// Which seam side covers a loop edge (the edge from loop position k to k + 1).
struct EdgeCover {
  int seam = -1;  ///< −1: a free edge
  int side = -1;  ///< 0: side a, 1: side b
};

/// The boundary units of a pattern.
struct BoundaryPlan {
  std::vector<BoundaryLoop> loops;            ///< per piece
  std::vector<std::array<SideRun, 2>> sides;  ///< per seam: sides a and b
  /// Per seam: the side indices (ascending, from 0 to the last side vertex) where
  /// either side has a break point; the seam is resampled range by range between them.
  std::vector<std::vector<int>> splits;
  /// Per piece: the loop positions (ascending) where its units start: its break points
  /// and the ends of the seam ranges on it (never empty).
  std::vector<std::vector<int>> unit_starts;
  std::vector<std::vector<EdgeCover>> cover;  ///< per piece, per loop edge

  int num_units(int piece) const {
    return static_cast<int>(unit_starts[static_cast<size_t>(piece)].size());
  }
  /// Whether a pinned boundary lies on a hole's rim (its first vertex is off the loop).
  bool on_hole(const PinnedBoundary& pin) const;
};

/// Cuts every piece's boundary loop into units. Throws InputError when a seam's sides
/// differ in vertex count or have fewer than 2 vertices, a seam side or open pinned
/// boundary is not a run of consecutive boundary vertices, or a boundary edge is on two
/// seam sides.
BoundaryPlan plan_boundary(const Pattern& pattern);

/// A sample of a seam in its index space: between side vertices i and i + 1 at
/// parameter t ∈ [0, 1) (t = 0: side vertex i itself).
struct SeamSample {
  int i = 0;
  double t = 0.0;
};

/// The new vertices of one seam, the same for both sides.
struct SeamResampling {
  std::vector<SeamSample> samples;  ///< all ranges concatenated, shared ends once
  std::vector<int> range_offset;    ///< per range: its first sample; then the last sample
};

/// Resamples every seam (BoundaryPlan::splits ranges): a seam with a piece in `remesh`
/// (per piece) gets, per range, n = seam_edge_count of the mean 2D rest length of its
/// sides at the mean of the two pieces' `edge_length` (m) edges, sampled at the
/// fractions k/n of the 3D arc length of side a at `positions` (n_g×3, m; the old
/// garment's equilibrium, where both sides are welded); another seam keeps its side
/// vertices.
std::vector<SeamResampling> resample_seams(const Garment& old_garment, const Points3& positions,
                                           const BoundaryPlan& plan,
                                           const std::vector<bool>& remesh,
                                           const std::vector<double>& edge_length);

}  // namespace tightfit
