#pragma once
/// From a layout to initial pattern pieces: flatten every panel (flatten.hpp), check
/// it, rotate it into its grain frame, scale it down, resample its boundary (seam sides
/// with matching vertex counts at the same arc-length fractions of the 3D seam) and
/// mesh it in 2D (piece_mesher.hpp). Every pattern vertex keeps its place on the 3D
/// panel, so the pattern can be embedded on the body.
#include <string>
#include <vector>

#include "tightfit/garment/flatten.hpp"
#include "tightfit/garment/layout.hpp"
#include "tightfit/garment/pattern.hpp"
#include "tightfit/garment/pattern_options.hpp"
#include "tightfit/garment/triangle_locator.hpp"

namespace tightfit {

/// A point of a 3D panel: a panel face and barycentric weights of its three corners.
struct PanelPoint {
  int face = -1;
  Vec3 weights = Vec3::Zero();
};

/// How one piece relates to its panel. Piece coordinates are
/// `piece = linear · flat + offset`, `flat` being the flattened panel (m).
struct PieceMap {
  int panel = -1;                  ///< index into Layout::panels
  Points2 flat;                    ///< flattened panel vertices (n_panel × 2, m), before scaling
  Mat2 linear = Mat2::Identity();  ///< rotation into the grain frame, then scale-down
  Vec2 offset = Vec2::Zero();      ///< m
  DistortionReport distortion;     ///< of the flattening (before scaling)
  int arap_iterations = 0;
  /// Per piece vertex: where it lies on the panel (interior vertices outside the flat
  /// panel, possible next to concave boundary parts, use the nearest face with
  /// extrapolated weights).
  std::vector<PanelPoint> location;
};

/// Per seam: the lengths of its two sides after flattening, before scaling (m).
struct SeamReport {
  std::string name;
  double length_3d = 0.0;
  double length_a = 0.0;
  double length_b = 0.0;
  double relative_difference = 0.0;  ///< |a − b| / max(a, b)
  int vertices = 0;                  ///< vertices per side in the pattern
};

struct PatternBuild {
  Pattern pattern;                ///< one piece per panel, in panel order
  std::vector<PieceMap> maps;     ///< one per piece
  std::vector<SeamReport> seams;  ///< one per seam of the pattern
};

/// Builds the pattern. Throws InputError (source: layout.source) when a panel overlaps
/// itself when flattened, a seam's sides differ by more than layout.seam_tolerance, or
/// a resampled piece boundary crosses itself (edge length too long for the piece).
PatternBuild build_pattern(const Layout& layout, const PatternOptions& options);

/// The point of the panel (its face and barycentric weights) of a point in piece
/// coordinates (m); `locator` over the panel's faces at map.flat (one for many points).
PanelPoint locate_in_panel(const TriangleLocator& locator, const PieceMap& map,
                           const Vec2& piece_point);
/// 3D position of a panel point.
Vec3 panel_position(const Layout& layout, const PieceMap& map, const PanelPoint& point);

}  // namespace tightfit
