#include "tightfit/objectives/point_field.hpp"

#include <nanoflann.hpp>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace tightfit {
namespace {

/// nanoflann dataset adaptor over the rows of a Points3.
struct Cloud {
  const Points3* points = nullptr;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points->rows()); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const {
    return (*points)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
  }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                   Cloud, 3, std::size_t>;

}  // namespace

struct PointField::Index {
  Points3 points;  // own copy: the tree refers to it
  Cloud cloud;
  std::unique_ptr<KdTree> tree;

  explicit Index(const Points3& p) : points(p) {
    cloud.points = &points;
    tree = std::make_unique<KdTree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  }
};

PointField::PointField(Points3 points, VecX values, double radius)
    : points_(std::move(points)), values_(std::move(values)), radius_(radius) {
  if (points_.rows() == 0) throw std::invalid_argument("PointField: no points");
  if (values_.size() != points_.rows())
    throw std::invalid_argument("PointField: one value per point expected");
  if (!(radius_ > 0.0) || !std::isfinite(radius_) || !points_.allFinite() || !values_.allFinite())
    throw std::invalid_argument("PointField: non-finite input or radius <= 0");
  index_ = std::make_shared<const Index>(points_);
}

PointField::Evaluation PointField::evaluate(const Vec3& x) const {
  Evaluation ev;
  const double h2 = radius_ * radius_;
  std::vector<std::pair<std::size_t, double>> found;
  index_->tree->radiusSearch(x.data(), h2, found, nanoflann::SearchParams(32, 0.0f, false));
  double u_max = 0.0;
  for (const auto& [k, d2] : found) u_max = std::max(u_max, 1.0 - d2 / h2);
  if (found.empty() || !(u_max > 0.0)) {
    std::size_t nearest = 0;
    double d2 = 0.0;
    index_->tree->knnSearch(x.data(), 1, &nearest, &d2);
    ev.value = values_[static_cast<Eigen::Index>(nearest)];
    return ev;
  }
  // φ_k = u_k⁴ with u = 1 − r²/h², scaled by 1/u_max⁴; ∇φ_k = −8 u_k³ (x − c_k) / h².
  double sum_w = 0.0, sum_ws = 0.0;
  Vec3 sum_dw = Vec3::Zero(), sum_dws = Vec3::Zero();
  for (const auto& [k, d2] : found) {
    const auto kk = static_cast<Eigen::Index>(k);
    const Vec3 d = x - points_.row(kk).transpose();
    const double u = (1.0 - d.squaredNorm() / h2) / u_max;
    if (!(u > 0.0)) continue;
    const double w = u * u * u * u;
    const Vec3 dw = (-8.0 * u * u * u / (h2 * u_max)) * d;
    sum_w += w;
    sum_ws += w * values_[kk];
    sum_dw += dw;
    sum_dws += dw * values_[kk];
  }
  ev.value = sum_ws / sum_w;
  ev.gradient = (sum_dws - ev.value * sum_dw) / sum_w;
  return ev;
}

}  // namespace tightfit
