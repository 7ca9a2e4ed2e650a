#pragma once
/// Cutting a triangle surface by planes (and ellipsoids) so that every crossing becomes a polyline
/// of mesh edges: new vertices are inserted exactly on the planes and the crossed
/// triangles are split. Used to cut garment panels out of the body surface. A bone
/// region or a local plane (LayoutPlane::is_field, resolved by layout_anchors.hpp) is cut the same
/// way along the zero iso-line of its per-vertex field, taken as linear along every edge
/// (new vertices where the linear interpolant is zero, their field values interpolated
/// for the later cuts).
#include <vector>

#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The cut surface and what each of its elements comes from.
struct CutMesh {
  TriMesh mesh;                  ///< the cut surface (m), same orientation as the input
  std::vector<int> parent_face;  ///< per face: the input face it lies in
  /// on_plane[k][v]: vertex v lies on plane k (inserted there, snapped there, or within
  /// a tiny distance of it). One vector per plane, `mesh.num_vertices()` entries each.
  std::vector<std::vector<char>> on_plane;
  /// side[k][f]: +1 or −1, the side of plane k that face f lies on (a face lying in the
  /// plane counts as +1; for a bone region, +1 is where the field is positive).
  std::vector<std::vector<signed char>> side;
};

/// Cuts `mesh` by each plane in turn. A vertex whose distance to a plane is below
/// `snap_fraction` times the length of a crossing edge is moved onto the plane along
/// its tangent plane instead of creating a sliver triangle (only vertices not already
/// placed on an earlier plane, and only when the plane is not nearly tangent there); for
/// a bone region such a vertex moves along its edge onto the iso-line, every field's
/// value moving with it.
/// Planes must be resolved: std::invalid_argument for a plane with an unresolved anchor
/// or a bone region whose field does not have one value per vertex of `mesh`.
CutMesh cut_by_planes(const TriMesh& mesh, const std::vector<LayoutPlane>& planes,
                      double snap_fraction = 0.1);

/// The same, then by each opening's ellipsoid: `on_plane` and `side` have the planes'
/// entries first, then one per opening (side −1: inside the opening). New vertices of
/// an opening lie on its ellipsoid to round-off (Newton along the crossed edge).
CutMesh cut_by_planes_and_openings(const TriMesh& mesh, const std::vector<LayoutPlane>& planes,
                                   const std::vector<LayoutOpening>& openings,
                                   double snap_fraction = 0.1);

}  // namespace tightfit
