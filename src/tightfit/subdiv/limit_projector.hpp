#pragma once
/// Closest points on a LimitSurface (docs/design.md §6 items 3-5).
///
/// A start point comes from a kd-tree over a few limit samples per face (or from a
/// caller's hint); Newton's method on E(u,v) = ½|x(u,v) - p|² then refines it, stepping
/// with LimitSurface::walk so that steps cross faces without extrapolating. Safeguards:
/// Gauss-Newton (with a tiny Levenberg-Marquardt shift) when the Newton matrix is not
/// positive definite, steps capped to half a face in (u,v), and a backtracking line
/// search that only accepts strict decreases of the distance. The result is therefore
/// never farther from p than the start point, even near extraordinary vertices where
/// the parametrization is singular and Gregory-patch derivatives do not exactly match
/// positions.
#include <memory>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/point_cloud_index.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// Newton refinement of the closest point to `p` (m) starting at `start`.
/// `control`: num_control_vertices × 3 positions (m).
SurfacePoint refine_closest_point(const LimitSurface& surface, const Points3& control,
                                  const Vec3& p, SurfacePoint start);

/// Closest-point queries for one set of control positions. Keeps a reference to the
/// surface (which must outlive it) and a copy of the positions.
class LimitProjector {
 public:
  /// Samples every face at the centroids of its samples_per_edge² sub-triangles.
  LimitProjector(const LimitSurface& surface, const Points3& control, int samples_per_edge = 3);
  ~LimitProjector();
  LimitProjector(const LimitProjector&) = delete;
  LimitProjector& operator=(const LimitProjector&) = delete;

  const Points3& control() const { return control_; }
  /// The limit sample nearest to p.
  SurfacePoint nearest_sample(const Vec3& p) const;
  /// Closest point: Newton from the nearest sample.
  SurfacePoint project(const Vec3& p) const;

 private:
  const LimitSurface& surface_;
  Points3 control_;
  std::vector<SurfacePoint> samples_;  ///< the limit samples, in the order they are indexed
  std::unique_ptr<PointCloudIndex> sample_index_;  ///< their positions (m)
};

}  // namespace tightfit
