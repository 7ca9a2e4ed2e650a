#include "tightfit/objectives/point_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tightfit/geometry/point_cloud_index.hpp"

namespace tightfit {

PointField::PointField(Points3 points, VecX values, double radius)
    : points_(std::move(points)), values_(std::move(values)), radius_(radius) {
  if (points_.rows() == 0) throw std::invalid_argument("PointField: no points");
  if (values_.size() != points_.rows())
    throw std::invalid_argument("PointField: one value per point expected");
  if (!(radius_ > 0.0) || !std::isfinite(radius_) || !points_.allFinite() || !values_.allFinite())
    throw std::invalid_argument("PointField: non-finite input or radius <= 0");
  index_ = std::make_shared<const PointCloudIndex>(points_);
}

PointField::Evaluation PointField::evaluate(const Vec3& x) const {
  Evaluation ev;
  const double h2 = radius_ * radius_;
  const std::vector<PointCloudIndex::Neighbour> near = index_->within(x, radius_);
  double u_max = 0.0;
  for (const PointCloudIndex::Neighbour& n : near) u_max = std::max(u_max, n.u);
  if (near.empty()) {
    ev.value = values_[index_->nearest(x)];
    return ev;
  }
  // φ_k = u_k⁴ with u = 1 − r²/h², scaled by 1/u_max⁴; ∇φ_k = −8 u_k³ (x − c_k) / h².
  double sum_w = 0.0, sum_ws = 0.0;
  Vec3 sum_dw = Vec3::Zero(), sum_dws = Vec3::Zero();
  for (const PointCloudIndex::Neighbour& n : near) {
    const Vec3 d = x - points_.row(n.k).transpose();
    const double u = n.u / u_max;
    const double w = u * u * u * u;
    const Vec3 dw = (-8.0 * u * u * u / (h2 * u_max)) * d;
    sum_w += w;
    sum_ws += w * values_[n.k];
    sum_dw += dw;
    sum_dws += dw * values_[n.k];
  }
  ev.value = sum_ws / sum_w;
  ev.gradient = (sum_dws - ev.value * sum_dw) / sum_w;
  return ev;
}

}  // namespace tightfit
