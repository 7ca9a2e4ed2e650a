#pragma once
/// Neighbour queries on a fixed point set for the compact-kernel fields of the
/// objectives layer (the IMLS surface, the point field): the points within a radius with
/// their kernel argument u = 1 − r²/h², and the nearest point. A kd-tree (nanoflann).
/// Internal to the objectives layer.
#include <memory>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

class PointCloudIndex {
 public:
  /// A copy of `points` (k×3, m) is indexed.
  explicit PointCloudIndex(const Points3& points);
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
