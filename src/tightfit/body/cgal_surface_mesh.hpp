#pragma once
/// Conversions between tightfit's TriMesh and CGAL's Surface_mesh (EPICK kernel), shared
/// by the body-surface operations that use CGAL Polygon Mesh Processing. Internal to the
/// body layer; the types are CGAL's.
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit::cgal_surface {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

/// The TriMesh as a Surface_mesh (same vertex order). Throws InputError(source) naming
/// the first face that makes it non-manifold or inconsistently oriented.
Mesh to_cgal(const TriMesh& m, const std::string& source);
/// The Surface_mesh's live vertices and faces as a TriMesh (vertices renumbered densely).
TriMesh from_cgal(const Mesh& mesh);
/// Length of the diagonal of the mesh's bounding box (m).
double bbox_diagonal(const Mesh& mesh);

}  // namespace tightfit::cgal_surface
