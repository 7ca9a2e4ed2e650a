#pragma once
/// The pinned "bone" core of a body (docs/design.md §3, §8): volume vertices held fixed so
/// that the body does not float and its stiffness matrix is non-singular.
#include <optional>
#include <string>
#include <vector>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Which interior vertices are pinned: the union of
///  * every vertex deeper than `soft_tissue` below the surface (when set),
///  * every vertex within `bone_radius` of one of `bones` (and their samples), and
///  * the vertices of `embedded_core` and every vertex inside it.
/// Surface vertices are never pinned.
struct CoreOptions {
  std::optional<double> soft_tissue;  ///< soft-tissue thickness (m), > 0
  std::vector<BoneSegment> bones;     ///< bone segments (m), in the body's frame
  double bone_radius = 0.01;          ///< pin radius around bone segments (m), ≥ 0
  /// Spacing (m) of the points sampled along the bones and inserted as volume vertices
  /// (so that every bone inside the body carries pinned vertices); 0 = no samples.
  double bone_sample_spacing = 0.0;
  /// Samples closer than this to the surface (m) are not inserted (they would make
  /// flat tets next to the surface).
  double bone_sample_clearance = 0.0;
  /// A closed, outward-oriented surface strictly inside the body (e.g. a bone, or the
  /// concentric core of a generator body) that is built into the tet mesh as internal
  /// faces, so the pinned region has exactly this boundary. Empty = none.
  TriMesh embedded_core;
  /// Name used in error messages (e.g. "spec.json: /core").
  std::string source = "core";
};

/// Points (k×3, m) along `options.bones` every `bone_sample_spacing` (both ends
/// included), keeping those inside the surface and at least `bone_sample_clearance` from
/// it. Empty when there are no bones or the spacing is 0.
Points3 bone_sample_points(const CoreOptions& options, const SurfaceDistance& surface);

/// The pinned vertices (sorted, unique) of `volume`, whose first `num_surface_vertices`
/// vertices are the surface, followed by `num_always_pinned` vertices that are pinned
/// in any case (the embedded core's vertices and the bone samples, see
/// tetrahedralize_surface). Throws InputError (source `options.source`) if no vertex is
/// pinned, saying how deep the deepest vertex is.
std::vector<int> pinned_core(const TetMesh& volume, int num_surface_vertices,
                             const SurfaceDistance& surface, const CoreOptions& options,
                             int num_always_pinned = 0);

}  // namespace tightfit
