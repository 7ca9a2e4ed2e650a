#pragma once
/// Neighbour queries on a fixed point set: the points within a radius with their kernel
/// argument u = 1 − r²/h² (the compact-kernel fields of the objectives: the IMLS surface,
/// the point field), and the nearest point (the limit-surface projector's start points).
/// A kd-tree (nanoflann).
#include <memory>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

class PointCloudIndex {
 public:
  /// `points` (k×3, m) are kept and indexed.
  explicit PointCloudIndex(Points3 points);
  ~PointCloudIndex();
  PointCloudIndex(const PointCloudIndex&) = delete;
  PointCloudIndex& operator=(const PointCloudIndex&) = delete;

  struct Neighbour {
    Eigen::Index k;  ///< point index
    double u;        ///< 1 − ‖x − c_k‖²/h², in (0, 1]
  };
  /// The points strictly within `radius` h of x.
  std::vector<Neighbour> within(const Vec3& x, double radius) const;
  /// Index of the point nearest to x.
  Eigen::Index nearest(const Vec3& x) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace tightfit
