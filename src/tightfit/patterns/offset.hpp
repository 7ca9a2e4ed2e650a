#pragma once
/// Outward offset of a pattern outline by a per-edge distance: the cut line around
/// the sew line. Works in whatever length unit the caller uses (the exports use mm).
#include <vector>

#include "tightfit/common/planar.hpp"  // signed_area of a Polygon2
#include "tightfit/common/types.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// A closed polygon: points in order, the last point not repeated.
using Polygon2 = std::vector<Vec2>;

/// Area centroid of a closed polygon with non-zero area.
Vec2 area_centroid(const Polygon2& polygon);

/// Outward offset of the simple counter-clockwise polygon `polygon`: every edge i
/// (from point i to point i+1, cyclically) moves outward by `distance[i]` ≥ 0.
/// Convex corners are mitred (the two offset edge lines meet) unless the mitre point is
/// farther than `mitre_limit` × the larger of the two distances from the corner, or
/// `style` is Round: then a circular arc (radius blending from one distance to the
/// other) is drawn with chord error ≤ `arc_tolerance`. Where edges of different
/// distance meet in a straight line, the cut line steps perpendicularly. Concave corners
/// and parts where the offset overlaps itself (curves tighter than the allowance,
/// slits narrower than twice the allowance) are resolved by keeping only the outer
/// envelope of the raw offset curve. Returns a simple counter-clockwise polygon.
/// Throws SolverError if the envelope cannot be traced (degenerate input).
Polygon2 offset_polygon(const Polygon2& polygon, const std::vector<double>& distance,
                        CornerStyle style, double mitre_limit, double arc_tolerance);

}  // namespace tightfit
