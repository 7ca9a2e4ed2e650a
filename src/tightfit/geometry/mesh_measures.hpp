#pragma once
/// Geometric measures of triangle and tetrahedral meshes. Lengths in the mesh's units
/// (metres inside tightfit), areas in units², volumes in units³, angles in degrees.
/// None of these validates its input; degenerate elements give zero areas/normals.
#include <array>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

// ---- surfaces ----------------------------------------------------------------------

/// Signed enclosed volume Σ_f a·(b×c)/6 of a closed surface; positive when the faces
/// are counter-clockwise seen from outside. Meaningless for open surfaces.
double signed_volume(const TriMesh& mesh);
/// Area of the triangle (a, b, c) (units², ≥ 0).
double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c);
/// Area of face `f` of `mesh`.
double face_area(const TriMesh& mesh, int f);
/// Total surface area.
double surface_area(const TriMesh& mesh);
/// Area of each face (m entries).
VecX face_areas(const TriMesh& mesh);
/// Unit normal of each face (m×3), right-handed in corner order; zero rows for
/// zero-area faces.
Points3 face_normals(const TriMesh& mesh);
/// Area-weighted vertex normals, normalized (n×3); zero rows for unused vertices.
Points3 vertex_normals(const TriMesh& mesh);

/// Statistics of the lengths of the distinct edges of a mesh (count 0 and all values
/// 0 when there are no edges).
struct EdgeLengthStats {
  int count = 0;
  double min = 0.0;
  double max = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double rms = 0.0;
};
EdgeLengthStats edge_length_stats(const TriMesh& mesh);
/// Same for the distinct edges of a tet mesh (6 per tet, shared ones counted once).
EdgeLengthStats edge_length_stats(const TetMesh& mesh);

// ---- tetrahedra --------------------------------------------------------------------

/// Signed volume (b-a)·((c-a)×(d-a))/6 of tet (a,b,c,d); positive for TetMesh's
/// orientation convention.
double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Signed volume of each tet (m entries).
VecX tet_volumes(const TetMesh& mesh);
/// Sum of the signed tet volumes.
double total_volume(const TetMesh& mesh);

/// The six interior dihedral angles (degrees) of a tet at its edges
/// (ab, ac, ad, bc, bd, cd); zeros if a face is degenerate.
std::array<double, 6> tet_dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d);
/// Smallest and largest dihedral angle (degrees) over all tets; {0, 0} for no tets.
struct AngleRange {
  double min_degrees = 0.0;
  double max_degrees = 0.0;
};
AngleRange dihedral_angle_range(const TetMesh& mesh);

/// Radius-edge ratio: circumradius / shortest edge (√6/4 ≈ 0.612 for a regular tet,
/// +inf for a degenerate one).
double tet_radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Radius-edge ratio of each tet (m entries).
VecX radius_edge_ratios(const TetMesh& mesh);

}  // namespace tightfit
