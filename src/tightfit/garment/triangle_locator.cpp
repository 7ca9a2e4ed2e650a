#include "tightfit/garment/triangle_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tightfit/garment/triangle_geometry.hpp"

namespace tightfit {
namespace {

/// Each triangle's box is widened by this fraction of its diagonal, so that a point
/// within kContainsTolerance of a triangle lies in its box.
constexpr double kBoxMargin = 1e-9;

}  // namespace

TriangleLocator::TriangleLocator(const Triangles& triangles, const Points2& points)
    : triangles_(triangles), points_(points) {
  const int nt = num_triangles();
  box_.setEmpty();
  for (int t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) box_.extend(points_.row(triangles_(t, c)).transpose());
  cells_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(nt))));
  if (nt > 0) extent_ = (box_.max() - box_.min()).cwiseMax(1e-300);
  cell_size_ = extent_ / cells_;
  grid_.assign(static_cast<size_t>(cells_ * cells_), {});
  for (int t = 0; t < nt; ++t) {
    Eigen::AlignedBox2d b;
    for (int c = 0; c < 3; ++c) b.extend(points_.row(triangles_(t, c)).transpose());
    const Vec2 margin = Vec2::Constant(kBoxMargin * b.diagonal().norm());
    const int i0 = cell_x(b.min().x() - margin.x()), i1 = cell_x(b.max().x() + margin.x());
    const int j0 = cell_y(b.min().y() - margin.y()), j1 = cell_y(b.max().y() + margin.y());
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) grid_[static_cast<size_t>(i * cells_ + j)].push_back(t);
  }
}

int TriangleLocator::cell_x(double x) const {
  const double s = (x - box_.min().x()) / extent_.x() * cells_;
  return std::clamp(static_cast<int>(std::clamp(s, -1.0, 1.0 * cells_)), 0, cells_ - 1);
}

int TriangleLocator::cell_y(double y) const {
  const double s = (y - box_.min().y()) / extent_.y() * cells_;
  return std::clamp(static_cast<int>(std::clamp(s, -1.0, 1.0 * cells_)), 0, cells_ - 1);
}

Vec3 TriangleLocator::weights(int t, const Vec2& q) const {
  return barycentric_2d(q, points_.row(triangles_(t, 0)), points_.row(triangles_(t, 1)),
                        points_.row(triangles_(t, 2)));
}

Vec3 TriangleLocator::closest_weights(int t, const Vec2& q) const {
  return closest_point_weights_2d(q, points_.row(triangles_(t, 0)), points_.row(triangles_(t, 1)),
                                  points_.row(triangles_(t, 2)));
}

double TriangleLocator::squared_distance(int t, const Vec2& q) const {
  const Vec2 a = points_.row(triangles_(t, 0)), b = points_.row(triangles_(t, 1)),
             c = points_.row(triangles_(t, 2));
  const Vec3 w = closest_point_weights_2d(q, a, b, c);
  return (w[0] * a + w[1] * b + w[2] * c - q).squaredNorm();
}

int TriangleLocator::containing(const Vec2& q, const std::function<bool(int)>& accept) const {
  if (num_triangles() == 0 || !q.allFinite()) return -1;
  for (int t : cell(cell_x(q.x()), cell_y(q.y()))) {
    const Vec2 a = points_.row(triangles_(t, 0)), b = points_.row(triangles_(t, 1)),
               c = points_.row(triangles_(t, 2));
    Mat2 edges;
    edges << b - a, c - a;
    if (edges.determinant() == 0.0) continue;  // degenerate: contains no point
    if (barycentric_2d(q, a, b, c).minCoeff() >= -kContainsTolerance && (!accept || accept(t)))
      return t;
  }
  return -1;
}

int TriangleLocator::nearest(const Vec2& q) const {
  if (num_triangles() == 0) throw std::invalid_argument("TriangleLocator: no triangles");
  if (!q.allFinite()) throw std::invalid_argument("TriangleLocator: the point is not finite");
  const int ci = cell_x(q.x()), cj = cell_y(q.y());
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  auto visit = [&](int i, int j) {
    if (i < 0 || i >= cells_ || j < 0 || j >= cells_) return;
    for (int t : cell(i, j)) {
      const double d = squared_distance(t, q);
      if (d < best_d || (d == best_d && t < best)) {
        best_d = d;
        best = t;
      }
    }
  };
  // Rings of cells around q's cell; a triangle not met yet lies beyond an inner side of
  // the rectangle of the cells seen, so its distance is at least that side's distance.
  const double slack = 1e-9 * (box_.max() - box_.min()).norm();
  for (int r = 0;; ++r) {
    if (r == 0) {
      visit(ci, cj);
    } else {
      for (int j = cj - r; j <= cj + r; ++j) {
        visit(ci - r, j);
        visit(ci + r, j);
      }
      for (int i = ci - r + 1; i <= ci + r - 1; ++i) {
        visit(i, cj - r);
        visit(i, cj + r);
      }
    }
    const int i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
    double bound = std::numeric_limits<double>::infinity();
    if (i0 > 0) bound = std::min(bound, q.x() - (box_.min().x() + i0 * cell_size_.x()));
    if (i1 < cells_ - 1)
      bound = std::min(bound, box_.min().x() + (i1 + 1) * cell_size_.x() - q.x());
    if (j0 > 0) bound = std::min(bound, q.y() - (box_.min().y() + j0 * cell_size_.y()));
    if (j1 < cells_ - 1)
      bound = std::min(bound, box_.min().y() + (j1 + 1) * cell_size_.y() - q.y());
    if (bound == std::numeric_limits<double>::infinity()) break;  // every cell seen
    if (best >= 0 && bound > std::sqrt(best_d) + slack) break;
  }
  return best;
}

}  // namespace tightfit
