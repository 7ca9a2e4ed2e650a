#pragma once
/// A smooth scalar field in space from values at points (Shepard interpolation with a
/// compactly supported kernel), e.g. the skin weight of a set of bones carried from a
/// rig mesh's vertices to any point near the body:
///   f(x) = Σ_k φ(‖x − c_k‖) s_k / Σ_k φ(‖x − c_k‖),   φ(r) = (1 − r²/h²)⁴ for r < h,
/// with c_k the points (m), s_k their values and h the radius (m). f is a weighted mean
/// of the values within h (so it stays within their range) and C³ wherever a point lies
/// within h; elsewhere f is the value of the NEAREST point (gradient 0), continuous where
/// the last point leaves the h-ball. Kernel weights are taken relative to the largest,
/// so nothing underflows near the cut-off. Neighbours: PointCloudIndex.
#include <memory>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/point_cloud_index.hpp"

namespace tightfit {

class PointField {
 public:
  /// `points` k×3 (k >= 1), `values` k, radius h > 0 (m). Throws std::invalid_argument
  /// for mismatched sizes, no points, non-finite input or h <= 0.
  PointField(Points3 points, VecX values, double radius);

  struct Evaluation {
    double value = 0.0;
    Vec3 gradient = Vec3::Zero();  ///< ∂f/∂x (1/m times the values' unit)
  };
  Evaluation evaluate(const Vec3& x) const;

 private:
  Points3 points_;
  VecX values_;
  double radius_ = 0.0;
  std::shared_ptr<const PointCloudIndex> index_;
};

}  // namespace tightfit
