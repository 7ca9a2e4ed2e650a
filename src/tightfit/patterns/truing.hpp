#pragma once
/// Truing of a pattern outline for the exports: the optimized boundary is a polyline
/// with small zig-zags (one vertex per mesh edge); a pattern maker "trues" it into a
/// smooth curve. Here: per stretch between kept points, a centripetal Catmull-Rom curve
/// through a reduced set of the polyline's points, sampled densely, refined until it
/// lies within a tolerance of the polyline. Works in the caller's length unit (the
/// exports use mm). Only the drawn outlines are trued, never the simulated pattern.
#include <vector>

#include "tightfit/patterns/offset.hpp"

namespace tightfit {

/// A trued closed outline.
struct TruedOutline {
  /// The curve's points, in the input's order and orientation; the last point is not
  /// repeated.
  Polygon2 points;
  /// Per point: the index of the input point it is (bit-identical), or −1 for a point
  /// sampled on the curve between input points.
  std::vector<int> source;
  /// Per edge k (point k → point k+1, cyclically): an input edge of the same stretch
  /// between kept points (input edge i runs from input point i to i+1), e.g. to look up
  /// the edge's seam allowance. Within a stretch every input edge has the same owner
  /// when every change of owner is a kept point.
  std::vector<int> edge_source;
};

/// Trues the closed polygon `polygon` (n ≥ 3 points). Points with `keep[i]` stay
/// exactly (same coordinates) on the curve and split it into stretches; at points with
/// `corner[i]` (implies keep) the curve may turn sharply, elsewhere it passes smoothly
/// (both stretches take the direction between the polygon's points 5 × sample_spacing of
/// arc length before and after the kept point as their tangent). Each stretch becomes a centripetal
/// Catmull-Rom curve through its end points and as few of its interior points as needed
/// for every point of the stretch's polyline to be within `tolerance` of the curve and
/// every point of the sampled curve within `tolerance` of the polyline; samples are at
/// most `sample_spacing` apart, and a segment of the curve that is straight is not
/// sampled. Where even the curve through all points stays farther than the tolerance,
/// that polyline edge is kept straight. `tolerance` ≤ 0 returns the input unchanged.
/// With no kept point at all, point 0 is kept. `keep` and `corner` have n entries.
TruedOutline true_outline(const Polygon2& polygon, const std::vector<bool>& keep,
                          const std::vector<bool>& corner, double tolerance, double sample_spacing);

/// Turning angle (radians, ≥ 0) of the closed polygon at point i: the angle between the
/// incoming and the outgoing edge direction (0 on a straight run).
double turning_angle(const Polygon2& polygon, size_t i);

}  // namespace tightfit
