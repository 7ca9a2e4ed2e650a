#pragma once
/// Isotropic remeshing of a user's closed body surface to the simulation resolution
/// (CGAL, GPL-3), with the cap borders of crop_and_cap and sharp creases kept as
/// feature lines.
#include <vector>

#include "tightfit/body/crop_and_cap.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

struct RemeshOptions {
  double edge_length = 0.015;  ///< target edge length (m), > 0
  int iterations = 5;  ///< CGAL isotropic remeshing iterations (split, collapse, flip, relax)
  /// Edges whose two faces' normals differ by more than this angle (degrees) are
  /// crease candidates; those that form closed loops at least `min_feature_loop_length`
  /// long (the rim of an existing cap) are feature edges. Open or short creases (toes,
  /// skin folds of a scan) are remeshed over. Use 180 for none.
  double sharp_angle_deg = 60.0;
  double min_feature_loop_length = 0.05;  ///< m
  /// Planes of caps made by `crop_and_cap`: faces with all corners on one of these
  /// planes are cap faces, and the edges between cap and non-cap faces are feature edges.
  std::vector<CropPlane> cap_planes;
  /// Local refinements of self-intersecting regions (see remesh_isotropic).
  int max_refinements = 3;
};

/// Result of remeshing with the number of feature edges kept.
struct RemeshResult {
  TriMesh mesh;
  int feature_edges = 0;  ///< constrained edges of the input (before splitting)
  int refinements = 0;    ///< local refinement rounds needed against self-intersections
};

/// Isotropic remeshing (CGAL::Polygon_mesh_processing::isotropic_remeshing) of a closed
/// surface to edges of about `edge_length`. Feature edges (see RemeshOptions) are split
/// and collapsed only along their polylines, and their vertices do not move (CGAL 5.5's
/// relaxation along constraints shrinks convex rims, so it is not used), so every
/// feature line stays inscribed in the input's. Other vertices are projected back onto
/// the input surface, so the volume changes only by the chord error of the new
/// resolution.
///
/// Where parts of the input are closer than about the edge length (closed lips, toes)
/// the uniform result can intersect itself. Then the faces around the intersections
/// (plus two rings) are remeshed again with half the edge length, their vertices
/// projected onto the original input, repeated with a quarter, an eighth ... up to
/// `max_refinements` times. Throws InputError (source "remesh") when the result is not
/// closed or still intersects itself.
RemeshResult remesh_isotropic(const TriMesh& surface, const RemeshOptions& options);

}  // namespace tightfit
