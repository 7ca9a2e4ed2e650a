#pragma once
/// Resampling of pattern piece boundaries, shared by the pattern builder
/// (pattern_builder.hpp) and remeshing during optimization (design/pattern_remesh.hpp):
/// a boundary loop is cut into runs (at corners, seam ends and pin ends), every run gets
/// an edge count from its length and the target edge length (both sides of a seam the
/// same count), and a run is sampled at even fractions of its arc length. The sampled
/// loops are then meshed by mesh_piece (piece_mesher.hpp).
#include <functional>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// A run of a closed boundary loop: its edges from loop position `first` to
/// `first + count` (positions taken modulo the loop size by the caller).
struct LoopRun {
  int first = 0;
  int count = 0;  ///< edges
};

/// Cuts `run` at every interior position p (first < p < first + count, not reduced
/// modulo the loop size) where `is_cut(p)` holds; the pieces in loop order.
std::vector<LoopRun> cut_run(const LoopRun& run, const std::function<bool(int)>& is_cut);

/// The fewest edges a run may get when its loop is cut into `runs` runs, so that the
/// loop keeps at least 3 vertices: 3 for one run, 2 for two, 1 for more.
int min_edge_count(int runs);

/// Edges of a run `length` long (m) at the target `edge_length` (m): the nearest
/// integer to length / edge_length, at least `min_edges`.
int edge_count(double length, double edge_length, int min_edges);

/// Edges of both sides of a seam, sides `length_a` and `length_b` long (m): the nearest
/// integer to their mean over `edge_length` (m), at least `min_a` and `min_b` (each
/// side's min_edge_count). Both sides get it, so their vertices pair up.
int seam_edge_count(double length_a, double length_b, double edge_length, int min_a, int min_b);

/// A point of a polyline: on its edge `edge` (from its vertex `edge` to `edge + 1`) at
/// parameter t ∈ [0, 1) (t = 0: the vertex itself).
struct ArcPoint {
  int edge = 0;
  double t = 0.0;
};

/// Cumulative lengths (m) along the polyline through the rows `path` of `points` (n×d,
/// m; d = 2 or 3): path.size() values, the first 0.
template <class Points>
std::vector<double> cumulative_lengths(const Points& points, const std::vector<int>& path) {
  std::vector<double> cum(1, 0.0);
  for (size_t k = 1; k < path.size(); ++k)
    cum.push_back(cum.back() + (points.row(path[k]) - points.row(path[k - 1])).norm());
  return cum;
}

/// The point at arc length `target` (m, in [0, cum.back()]) of a polyline with
/// cumulative lengths `cum` (cumulative_lengths; non-decreasing). On a vertex, the
/// last edge starting at it at t = 0 (the one before it at t → 1 rolls over). Throws
/// std::invalid_argument when `cum` has fewer than 2 values (no edge).
ArcPoint locate_arc(const std::vector<double>& cum, double target);

/// The points at the arc-length fractions k / n, k = 0 … n − 1, of the polyline with
/// cumulative lengths `cum` (locate_arc). Throws std::invalid_argument when n < 1 or
/// `cum` has no edge.
std::vector<ArcPoint> sample_arc(const std::vector<double>& cum, int n);

/// The rows of a polygon from its points (k×2, m).
Points2 polygon_rows(const std::vector<Vec2>& points);

}  // namespace tightfit
