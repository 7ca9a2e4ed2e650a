#pragma once
/// The loops along which a plane cuts a closed triangle surface, and the part of the
/// surface beyond one of them: what a local crop removes (a hand beyond the wrist loop)
/// while the rest of the body behind the same plane stays.
#include <string>
#include <utility>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The part of a closed 2-manifold beyond one loop of a plane's cut.
struct BeyondLoop {
  /// Per vertex: 1 when it lies beyond the loop (reached from the loop's negative side
  /// without crossing the loop), else 0.
  std::vector<char> beyond;
  /// The mesh edges (smaller index, larger index) the loop crosses, sorted.
  std::vector<std::pair<int, int>> loop_edges;
};

/// `side` holds one signed distance per vertex of `mesh` (m, negative behind the plane
/// through `point` with normal `normal`). The plane cuts the mesh's edges whose ends
/// have opposite signs (a zero counts as positive); crossed edges of one face belong to
/// one loop. Picks, among the loops that go around `point` in the plane (a limb's
/// cross-section around its bone), the one whose crossing points (linear interpolation
/// of `side`) come nearest to it; when none goes around it, the nearest loop. Marks
/// the vertices beyond it. Throws InputError(source, …) when no edge is crossed (the
/// plane misses the surface) or the loop does not separate the surface (a handle
/// through it).
BeyondLoop beyond_nearest_loop(const TriMesh& mesh, const std::vector<double>& side, const Vec3& point,
                               const Vec3& normal, const std::string& source);

}  // namespace tightfit
