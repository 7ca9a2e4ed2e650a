#pragma once
/// Cropping a user's closed body surface to the region under the garment, with every
/// cut closed by a flat cap (CGAL corefinement, GPL-3).
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// A cutting plane through `point` (m). The crop keeps the half-space the normal points
/// into; the normal need not be unit length but must be non-zero. A `local` crop removes
/// only the part beyond the plane's cut loop nearest to `point` (body/local_crop.hpp):
/// a hand at the wrist, not the leg behind the same plane.
struct CropPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
  bool local = false;
};

/// Crops the closed, outward-oriented, non-self-intersecting surface to the
/// intersection of the half-spaces (for local planes: see CropPlane), one plane after
/// the other, and closes every cut with a flat cap (a triangulated
/// planar polygon; the caps have long, thin triangles until remeshed). Vertices closer
/// to a plane than 1e-7 of the mesh's bounding-box diagonal are first pushed to that
/// distance (on their side), so that no cut point nearly coincides with a vertex. Planes that miss
/// the surface leave it unchanged (local planes: an InputError). Throws InputError (source "crop")
/// if a plane removes the whole surface or the cut cannot be closed into a manifold, and when CGAL
/// finds the surface self-intersecting near a cut.
TriMesh crop_and_cap(const TriMesh& surface, const std::vector<CropPlane>& planes);

}  // namespace tightfit
