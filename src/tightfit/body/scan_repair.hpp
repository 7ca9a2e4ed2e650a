#pragma once
/// Repairs of a scanned body surface (CGAL Polygon Mesh Processing, GPL-3):
/// duplicate, degenerate and non-manifold elements, and small holes. scan_import.hpp
/// puts them together with the choice of the body's component and its units. A scan of
/// a million triangles needs no decimation: the isotropic remeshing of
/// surface_remeshing.hpp takes it to the simulation resolution in about 20 s
/// (docs/benchmarks.md). Shapes: a TriMesh has vertices n×3 (coordinates) and faces m×3
/// (vertex indices, counter-clockwise seen from outside).
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Duplicate vertices (same coordinates) merged, unused vertices, duplicate faces (same
/// corners in any order) and faces with a repeated corner removed, faces turned to
/// agree with their neighbours, non-manifold edges (three or more faces) and vertices
/// (faces around them not one fan) cut apart by duplicating their vertices
/// (CGAL repair_polygon_soup, orient_polygon_soup), then zero-area faces collapsed or
/// flipped away (remove_degenerate_faces). Coordinates in any unit, kept as they are.
/// The result is manifold and consistently oriented per component, but may be open
/// (a cut non-manifold edge leaves a slit) and may have several components. One
/// warning (prefixed "`source`: ") says what was changed; none when nothing was.
/// Throws InputError(source) when coordinates are not finite, no face is left, or a
/// degenerate face cannot be removed (naming where).
TriMesh repair_mesh_elements(const TriMesh& mesh, const std::string& source,
                             std::vector<std::string>& warnings);

/// A hole of a surface: a closed loop of boundary edges. Lengths in the mesh's units.
struct SurfaceHole {
  double boundary_length = 0.0;  ///< sum of the loop's edge lengths
  int edges = 0;                 ///< edges on the loop
  Vec3 center = Vec3::Zero();    ///< mean of the loop's vertices
  bool faired = false;           ///< filled and faired (CGAL's fairing can fail: then only refined)
};

/// A connected surface after fill_small_holes.
struct FilledSurface {
  TriMesh mesh;                       ///< with the small holes filled
  std::vector<SurfaceHole> filled;    ///< holes filled, refined and (see `faired`) faired
  std::vector<SurfaceHole> unfilled;  ///< holes left open, largest first
  double hole_limit = 0.0;            ///< largest boundary length that is filled
  /// |enclosed volume| with the holes left open closed by flat fans from their centres
  /// (units³): a body opened at a limb end still counts as big, a flat sheet as nothing.
  double enclosed_volume = 0.0;
  double area = 0.0;  ///< of the input surface (units²)
};

/// Share of a surface's area that a hole may span and still be filled: a hole is small
/// when its boundary is no longer than the circumference of a disc of this share of the
/// surface's area, P ≤ √(4π · 0.005 · A) ≈ 0.25 √A. Scale-free: a whole body (1.9 m²)
/// gets its holes up to 0.35 m around filled (scanner gaps at the crown, soles,
/// armpits, an open wrist), not the neck or a thigh cut open; a forearm (0.15 m²)
/// nothing beyond 0.1 m.
inline constexpr double kSmallHoleAreaShare = 0.005;

/// Fills every hole of the connected, manifold, consistently oriented triangle surface
/// `surface` whose boundary length is at most √(4π kSmallHoleAreaShare A) (A: the
/// surface's area) with CGAL triangulate_refine_and_fair_hole (minimal-area
/// triangulation, refined to the density of the boundary, faired: curvature continuous
/// across the boundary). Holes longer than that, or that CGAL cannot triangulate, stay
/// open and are listed. Units: any, kept. Throws InputError(source) when the surface is
/// not manifold or not consistently oriented.
FilledSurface fill_small_holes(const TriMesh& surface, const std::string& source);

}  // namespace tightfit
