#pragma once
/// Cropping off one limb end of a closed body surface (a hand at the wrist, a foot at
/// the ankle, the head at the neck) without touching the rest of the body that lies
/// behind the same plane: only the part beyond the plane's cut loop nearest to the
/// plane's point is removed, and that loop is closed by a flat cap.
#include <string>

#include "tightfit/body/crop_and_cap.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The plane cuts the closed, outward-oriented 2-manifold `surface` (m) along one or
/// more closed loops. Removes the part of the surface beyond the loop nearest to
/// `plane.point` (the side the normal points away from, reached from that loop without
/// crossing it) and closes the loop with a flat cap (triangles in the plane, facing
/// against the normal). Vertices closer to the plane than 1e-7 of the bounding-box
/// diagonal are first pushed off it, keeping their side. Throws InputError(source, …)
/// when the plane misses the surface or the loop does not separate the surface (a
/// handle through it).
TriMesh crop_beyond_nearest_loop(const TriMesh& surface, const CropPlane& plane,
                                 const std::string& source);

}  // namespace tightfit
