#pragma once
/// Checks of user-supplied meshes, with messages that say exactly what is wrong
/// (which vertex, face, edge or tet; a few examples and the total count).
#include <filesystem>
#include <string>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// What a surface must satisfy besides finite coordinates, valid indices,
/// non-degenerate faces, manifold edges and vertices, and consistent orientation
/// (always required).
struct SurfaceRequirements {
  /// No holes (boundary edges); the enclosed signed volume must then be positive
  /// (faces counter-clockwise seen from outside).
  bool closed = true;
  /// Accept vertices that no face uses.
  bool allow_isolated_vertices = false;
  /// Run the (exact, O(m log m)) self-intersection test. It runs only when every
  /// other check passed, since it needs a manifold, consistently oriented mesh.
  bool check_self_intersections = true;
  /// A face is degenerate when it repeats a vertex or when
  /// 2·area ≤ degenerate_tolerance · (longest edge)² (a needle or a cap whose height
  /// is below this fraction of its length), including faces whose corners coincide.
  double degenerate_tolerance = 1e-10;
};

/// Every problem found, each as one sentence without the source name; empty when the
/// surface is valid. Checks that depend on an earlier failed check are skipped
/// (e.g. topology when indices are out of range).
std::vector<std::string> surface_problems(const TriMesh& mesh, const SurfaceRequirements& req = {});

/// Throws InputError(source, problems joined by "; ") if surface_problems is not empty.
void validate_surface(const TriMesh& mesh, const std::string& source,
                      const SurfaceRequirements& req = {});

struct TetRequirements {
  /// A tet is degenerate (zero volume) when 6·|volume| ≤ degenerate_tolerance ·
  /// (longest edge)³; a regular tet has 6·volume ≈ 0.71·edge³.
  double degenerate_tolerance = 1e-10;
};

/// Every problem of a tet mesh: no tets, non-finite coordinates, indices out of
/// range, repeated corners, inverted (negative volume) or zero-volume tets.
std::vector<std::string> tet_mesh_problems(const TetMesh& mesh, const TetRequirements& req = {});

/// Throws InputError(source, problems joined by "; ") if tet_mesh_problems is not empty.
void validate_tet_mesh(const TetMesh& mesh, const std::string& source,
                       const TetRequirements& req = {});

}  // namespace tightfit
