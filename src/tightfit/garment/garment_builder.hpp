#pragma once
/// The garment layer's entry point: body surface + layout spec + pattern options →
/// a Garment (pattern pieces, welded garment vertices, embedding on the limit surface).
///
/// Steps: make the spec's planes absolute on this body (layout_anchors.hpp: anchors on
/// the skeleton, bone regions), build the layout (layout.hpp: cut the body surface by the
/// spec's planes, or read the OBJ panels), optionally move its vertices onto the limit surface,
/// flatten and mesh the pieces (pattern_builder.hpp), weld the seam vertices (garment.hpp), and
/// embed every garment vertex: its point on the 3D panel (barycentric in the flattened
/// panel triangle that contains it) projected onto the Loop limit surface
/// (LimitSurface closest point, started from the body face the panel point lies on).
#include <string>
#include <vector>

#include "tightfit/body/body.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/garment/layout.hpp"
#include "tightfit/garment/layout_anchors.hpp"
#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/garment/pattern_builder.hpp"
#include "tightfit/garment/pattern_options.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// Flattening quality of one piece, for reports.
struct PieceReport {
  std::string name;
  DistortionReport distortion;  ///< of the unscaled flattening against the 3D panel
  PieceScale scale;             ///< applied scale-down
  int vertices = 0;             ///< pattern vertices
  int triangles = 0;
  double min_angle_deg = 0.0;  ///< smallest angle of the pattern mesh
};

/// The garment and everything it was made from (for reports, debugging and tests).
struct GarmentBuild {
  Garment garment;
  Layout layout;                    ///< panels (positions on the limit surface if projected)
  std::vector<PieceMap> maps;       ///< piece ↔ panel maps, one per piece
  std::vector<PieceReport> pieces;  ///< one per piece
  std::vector<SeamReport> seams;    ///< one per seam
  Points3 positions;                ///< garment vertex positions on the limit surface (m)
  /// Distance (m) from each garment vertex's panel point to its limit surface point.
  std::vector<double> projection_distance;
};

/// Builds the garment on a body whose surface (control mesh) is `control` and whose
/// limit surface is `limit` (built from `control`); `rig` is the body's skeleton and skin
/// weights, needed when the spec is anchored on them. Throws InputError for invalid
/// layouts (see layout_anchors.hpp, layout.hpp, pattern_builder.hpp).
GarmentBuild build_garment(const TriMesh& control, const LimitSurface& limit,
                           const LayoutSpec& spec, const PatternOptions& options,
                           const LayoutRig& rig = {});

/// The same on a body: its surface is the control mesh of `limit`.
inline GarmentBuild build_garment(const Body& body, const LimitSurface& limit,
                                  const LayoutSpec& spec, const PatternOptions& options,
                                  const LayoutRig& rig = {}) {
  return build_garment(body.surface, limit, spec, options, rig);
}

}  // namespace tightfit
