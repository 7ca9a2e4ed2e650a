#pragma once
/// Loop limit positions of the vertices of a closed control mesh, and the fit that moves
/// control points so that the limit surface passes through a target surface at the
/// vertices.
///
/// The garment lives on the Loop limit surface of the body's surface mesh (docs/design.md §2,
/// §6). That surface lies inside the control polyhedron wherever it is convex, so a
/// control mesh sampled on an analytic cylinder gives a limit surface of smaller radius.
/// `fit_loop_limit` corrects this by a fixed-point iteration on the control points.
///
/// Limit position of a vertex v of valence n with one-ring neighbours w_k (Loop 1987,
/// the masks OpenSubdiv's Loop scheme uses for smooth interior vertices):
///   v∞ = (1 − nχ) v + χ Σ_k w_k,   χ = 1 / (n + 3 / (8 β_n)),
///   β_n = (5/8 − (3/8 + ¼ cos(2π/n))²) / n.
#include <functional>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Limit positions (n×3, m) of all vertices of a closed, manifold triangle mesh.
/// The one-ring of vertex v is taken from the directed face edges v→w, so every face
/// must be oriented consistently (each neighbour then appears exactly once).
Points3 loop_limit_positions(const TriMesh& mesh);

/// Valence-dependent weight χ of the limit mask above (n ≥ 3).
double loop_limit_chi(int valence);

/// Maps a point to the closest point of the target surface (m → m).
using SurfaceProjector = std::function<Vec3(const Vec3&)>;

struct LimitFitOptions {
  int max_iterations = 100;  ///< fixed-point iterations at most
  /// Stop when every vertex's limit position is within this distance of its projection
  /// onto the target, relative to the mean edge length of the mesh.
  double relative_tolerance = 1e-8;
};

struct LimitFitResult {
  int iterations = 0;             ///< iterations done
  double max_residual = 0.0;      ///< max |project(v∞) − v∞| after the fit (m)
  double max_displacement = 0.0;  ///< max distance a control point moved (m)
};

/// Moves the control points of the closed mesh `mesh` so that the limit position of
/// every vertex lies on the target surface given by `project`:
///   repeat  v ← v + (project(v∞) − v∞)  for all vertices at once,
/// which converges because the limit operator is a contraction towards identity on the
/// displacements (its eigenvalues lie in (0, 1]). Each step moves a vertex along the
/// target's normal at its current limit point (for a sphere or a cylinder: a radial
/// rescaling). Topology is unchanged.
LimitFitResult fit_loop_limit(TriMesh& mesh, const SurfaceProjector& project,
                              const LimitFitOptions& options = {});

}  // namespace tightfit
