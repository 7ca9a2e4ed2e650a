#pragma once
/// Point location in a 2D triangle mesh (a flattened panel, a pattern piece's rest mesh)
/// with a uniform grid of triangle boxes: a query looks at the triangles of one grid cell,
/// or of rings of cells around it for the nearest triangle, instead of every triangle.
/// The answers are those of a scan over all triangles in index order.
#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "tightfit/common/types.hpp"

namespace tightfit {

class TriangleLocator {
 public:
  /// Barycentric tolerance of containing(): q is in a triangle when all its weights are
  /// at least −kContainsTolerance.
  static constexpr double kContainsTolerance = 1e-12;

  /// `triangles` (n_t×3) index rows of `points` (n×2, m); both are copied.
  TriangleLocator(const Triangles& triangles, const Points2& points);

  int num_triangles() const { return static_cast<int>(triangles_.rows()); }

  /// The lowest-index triangle containing q (m), within kContainsTolerance of its
  /// barycentric weights, for which `accept(triangle)` holds (no `accept`: every one);
  /// −1 when there is none. Degenerate triangles (zero area) contain no point.
  int containing(const Vec2& q, const std::function<bool(int)>& accept = {}) const;

  /// The lowest-index triangle among those of smallest distance to q (m), that distance
  /// measured to each triangle's closest point (closest_point_weights_2d). Throws
  /// std::invalid_argument when there are no triangles.
  int nearest(const Vec2& q) const;

  /// Barycentric weights of q in triangle t (barycentric_2d; extrapolated outside).
  Vec3 weights(int t, const Vec2& q) const;
  /// Weights of the point of triangle t closest to q (all ≥ 0).
  Vec3 closest_weights(int t, const Vec2& q) const;

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;
  const std::vector<int>& cell(int i, int j) const {
    return grid_[static_cast<size_t>(i * cells_ + j)];
  }
  double squared_distance(int t, const Vec2& q) const;

  Triangles triangles_;
  Points2 points_;
  Eigen::AlignedBox2d box_;             ///< of the triangles' corners
  Vec2 extent_ = Vec2::Ones();          ///< of box_ (m), at least 1e-300
  Vec2 cell_size_ = Vec2::Ones();       ///< m
  int cells_ = 1;                       ///< per axis
  std::vector<std::vector<int>> grid_;  ///< per cell: triangles whose box meets it, ascending
};

}  // namespace tightfit
