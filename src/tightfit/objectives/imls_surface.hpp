#pragma once
/// Implicit moving least squares (IMLS) distance to a target surface given as oriented
/// points (paper Eq. 28-29 as corrected in docs/design.md §4; Öztireli et al. 2009 style):
///   f(x) = Σ_k n_k·(x − c_k) φ(‖x − c_k‖) / Σ_k φ(‖x − c_k‖),
///   φ(r) = (1 − r²/h²)⁴ for r < h, 0 otherwise,
/// with c_k the target points (m), n_k their unit normals (outward) and h the cut-off
/// radius (m). f is a signed distance (m): positive on the side the normals point to.
/// Near a plane it is exactly the signed distance to the plane; on a target curved with
/// radius R it is biased towards the concave side by O(h²/R) (measured: 0.16 h²/(2R) on
/// a sphere): that bias is the floor of a shape fit, so choose h small against the
/// target's radii of curvature, yet larger than the distances the garment starts at
/// (beyond h the fallback below takes over), and the target points a few to a radius
/// (scene/optimization_setup.hpp samples a target mesh at h/2). f is C³ wherever some
/// target point lies within h (φ is C³ at r = h).
///
/// Fallback: where no target point lies within h, f(x) = n_k·(x − c_k) for the NEAREST
/// target point k (the signed distance to the tangent plane of the nearest point). This
/// continues the IMLS value smoothly where the last point leaves the h-ball (with a
/// single point in range IMLS gives exactly this), has gradient n_k, and is only
/// discontinuous across the Voronoi faces of the target points far from the target,
/// where the optimizer starts at most. It never divides by zero.
///
/// Numerics: the kernel weights are evaluated relative to the largest one,
/// w_k = (u_k / u_max)⁴ with u = 1 − r²/h², so nothing underflows near the cut-off.
/// Neighbours come from PointCloudIndex (a kd-tree).
#include <memory>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/point_cloud_index.hpp"

namespace tightfit {

class ImlsSurface {
 public:
  /// `points` and `normals` k×3 (k >= 1); normals are normalized here; `radius` h > 0 (m).
  /// Throws InputError (source "shape target") for mismatched sizes, no points,
  /// non-finite coordinates, a zero normal or h <= 0.
  ImlsSurface(Points3 points, Points3 normals, double radius);

  /// f(x) and ∇f(x) (unit-free: m/m).
  struct Evaluation {
    double value = 0.0;            ///< f(x), m
    Vec3 gradient = Vec3::Zero();  ///< ∇f(x)
    bool fallback = false;         ///< true when no target point lies within h
  };
  Evaluation evaluate(const Vec3& x) const;

  const Points3& points() const { return points_; }
  const Points3& normals() const { return normals_; }
  double radius() const { return radius_; }

 private:
  Points3 points_;
  Points3 normals_;
  double radius_ = 0.0;
  std::shared_ptr<const PointCloudIndex> index_;
};

}  // namespace tightfit
