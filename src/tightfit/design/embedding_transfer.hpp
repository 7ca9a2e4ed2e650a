#pragma once
/// Remeshing step 3 (pattern_remesh.hpp): the surface points of new pattern vertices,
/// interpolated in the old garment at its equilibrium and projected onto the body's
/// limit surface.
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/garment/triangle_locator.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// Transfers garment vertices of a remeshed pattern onto the limit surface, from the
/// old garment at an equilibrium. Keeps references to its arguments (keep them alive).
class EmbeddingTransfer {
 public:
  /// `old_garment` with its rest positions; `state` its equilibrium (surface points of
  /// its garment vertices, body positions); `positions` the 3D garment positions at
  /// that state (n_g × 3, m); `surface` the body's limit surface.
  EmbeddingTransfer(const Garment& old_garment, const EmbeddedState& state,
                    const Points3& positions, const LimitSurface& surface);

  /// Surface point of the old pattern vertex `v` (piece-local) of piece `piece`.
  SurfacePoint at_vertex(int piece, int v) const;
  /// Surface point at parameter t ∈ [0, 1) along the old edge from local vertex `from`
  /// to local vertex `to` of `piece` (t = 0: exactly vertex `from`).
  SurfacePoint on_edge(int piece, int from, int to, double t) const;
  /// Surface point of the 2D rest point `q` (m) of `piece`, located in the old rest
  /// mesh: the lowest-index triangle of positive area containing it, else the nearest
  /// triangle with the weights of its closest point (TriangleLocator).
  SurfacePoint at_rest_point(int piece, const Vec2& q) const;

 private:
  int garment_vertex(int piece, int v) const;
  SurfacePoint project(const Vec3& point, int hint_garment_vertex) const;

  const Garment& old_;
  const EmbeddedState& state_;
  const Points3& positions_;
  const LimitSurface& surface_;
  Points3 control_;
  std::vector<TriangleLocator> locators_;  // per old piece, of its rest mesh
};

}  // namespace tightfit
