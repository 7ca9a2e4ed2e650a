#pragma once
/// The loops along which a plane cuts a closed triangle surface, and the part of the
/// surface beyond one of them: what a local crop removes (a hand beyond the wrist loop)
/// while the rest of the body behind the same plane stays.
#include <string>
#include <utility>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The cut of a triangle mesh (closed or with boundaries) by a plane, given by one
/// signed distance per vertex (m, negative behind the plane; a zero counts as
/// positive): the crossed edges, the segment each crossed face holds, and the
/// connected pieces of the cut ("loops": crossed edges of one face belong to one).
struct PlaneCut {
  /// One segment of the cut: the part of face `face` between two crossed edges.
  struct Segment {
    int face = -1;
    int a = -1, b = -1;  ///< indices into `edges` of the face's two crossed edges
  };
  std::vector<std::pair<int, int>> edges;  ///< crossed edges (smaller, larger vertex index)
  /// Per crossed edge: where the plane crosses it, as the fraction t from the smaller
  /// vertex (0) to the larger (1), the zero of the linear interpolation of the distances.
  std::vector<double> t;
  std::vector<int> loop;          ///< per crossed edge: its loop, 0 … num_loops − 1
  std::vector<Segment> segments;  ///< one per crossed face, in face order
  int num_loops = 0;
  /// Per loop: 1 when every crossed edge of it lies in two crossed faces (the loop
  /// closes on itself); 0 when it ends on the mesh's boundary (an open polyline).
  std::vector<char> closed;
};

/// Cuts `mesh` by the plane whose signed distances `side` holds (one per vertex).
PlaneCut cut_by_plane(const TriMesh& mesh, const std::vector<double>& side);

/// The crossing point of crossed edge `i` of `cut` on `mesh` (m).
Vec3 crossing_point(const TriMesh& mesh, const PlaneCut& cut, int i);

/// The loop of `cut` nearest `point`: among the loops that go around `point` in the
/// plane with unit normal `normal` (a ray from it in the plane crosses an odd number of
/// their segments: a limb's cross-section around its bone), the one whose crossing
/// points come nearest to it; when none goes around it, the nearest loop (then
/// `encloses` is false). loop −1 when the cut is empty.
struct NearestCutLoop {
  int loop = -1;
  bool encloses = false;
  double distance = 0.0;  ///< from `point` to the loop's nearest crossing point (m)
};
NearestCutLoop nearest_cut_loop(const TriMesh& mesh, const PlaneCut& cut, const Vec3& point,
                                const Vec3& normal);

/// The length (m) of loop `loop` of `cut` on `mesh`: the sum of its segments' lengths.
double cut_loop_length(const TriMesh& mesh, const PlaneCut& cut, int loop);

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
BeyondLoop beyond_nearest_loop(const TriMesh& mesh, const std::vector<double>& side,
                               const Vec3& point, const Vec3& normal, const std::string& source);

}  // namespace tightfit
