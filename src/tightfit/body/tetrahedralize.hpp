#pragma once
/// Quality tetrahedralization of a closed surface with TetGen 1.5 (AGPL-3), keeping the
/// surface exactly: no Steiner points on the boundary (`-Y`), no merging of coplanar
/// facets (`-M`), so the boundary triangles of the result are the input triangles and
/// volume vertex i == surface vertex i for i < n_surface (the Body invariant, body.hpp).
#include <string>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Quality bounds handed to TetGen (`-q<max_radius_edge>/<min_dihedral_deg>`, `-a<max_volume>`).
struct TetQuality {
  /// Bound on circumradius / shortest edge of a tet (TetGen's radius-edge ratio); a
  /// regular tet has 0.612. Must be ≥ 1.0 (smaller bounds do not terminate).
  double max_radius_edge = 1.4;
  /// Minimum dihedral angle TetGen tries to reach (degrees, 0 ≤ θ ≤ 18; larger values do
  /// not terminate). Not guaranteed next to the fixed boundary: check the result.
  double min_dihedral_deg = 12.0;
  /// Bound on tet volume (m³); 0 = none. See `regular_tet_volume`.
  double max_volume = 0.0;
};

/// Volume of a regular tetrahedron with edge length `edge` (m → m³): edge³ / (6√2).
double regular_tet_volume(double edge);

/// The TetGen switches used for `quality`, e.g. "pYMq1.4/12a3.97e-07zQ".
std::string tetgen_switches(const TetQuality& quality);

/// Tetrahedralizes the volume bounded by the closed, outward-oriented, non-self-
/// intersecting triangle mesh `surface`. Optional constraints inside it:
///  * `interior_points` (k×3, m): extra vertices strictly inside (e.g. samples of bone
///    segments);
///  * `internal_surface`: a closed surface strictly inside (e.g. an embedded bone) whose
///    triangles become faces of the tet mesh (kept exactly, like the surface).
/// Volume vertices are, in order: the n_surface surface vertices, the internal surface's
/// vertices, the interior points, then TetGen's interior Steiner points. Tets are
/// returned positively oriented.
///
/// The input is validated first (TetGen 1.5.0 crashes on its own error path): the
/// surfaces must be closed, manifold, outward and free of (mutual) intersections, the
/// internal surface and points strictly inside. Throws std::invalid_argument for bad
/// quality bounds, InputError (source "surface", "internal surface" or "interior
/// points") for invalid input or when TetGen rejects it (tiny features, close facets),
/// SolverError on other TetGen failures or when the invariant above cannot be
/// established (checked at run time, also in Release builds).
TetMesh tetrahedralize_surface(const TriMesh& surface, const TetQuality& quality,
                               const Points3& interior_points = Points3(0, 3),
                               const TriMesh& internal_surface = TriMesh());

}  // namespace tightfit
