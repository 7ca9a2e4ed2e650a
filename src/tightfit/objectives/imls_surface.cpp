#include "tightfit/objectives/imls_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/point_cloud_index.hpp"

namespace tightfit {
namespace {

const std::string kImlsSource = "shape target";

}  // namespace

ImlsSurface::ImlsSurface(Points3 points, Points3 normals, double radius)
    : points_(std::move(points)), normals_(std::move(normals)), radius_(radius) {
  if (points_.rows() == 0) throw InputError(kImlsSource, "has no points");
  if (normals_.rows() != points_.rows())
    throw InputError(kImlsSource, "has " + std::to_string(points_.rows()) + " points but " +
                                      std::to_string(normals_.rows()) + " normals");
  if (!(radius_ > 0.0) || !std::isfinite(radius_))
    throw InputError(kImlsSource, "IMLS radius must be positive and finite");
  if (!points_.allFinite()) throw InputError(kImlsSource, "has non-finite point coordinates");
  for (Eigen::Index k = 0; k < normals_.rows(); ++k) {
    const double len = normals_.row(k).norm();
    if (!(len > 0.0) || !std::isfinite(len))
      throw InputError(kImlsSource, "normal " + std::to_string(k) + " is zero or not finite");
    normals_.row(k) /= len;
  }
  index_ = std::make_shared<const PointCloudIndex>(points_);
}

ImlsSurface::Evaluation ImlsSurface::evaluate(const Vec3& x) const {
  Evaluation ev;
  const double h2 = radius_ * radius_;
  const std::vector<PointCloudIndex::Neighbour> near = index_->within(x, radius_);
  double u_max = 0.0;
  for (const PointCloudIndex::Neighbour& n : near) u_max = std::max(u_max, n.u);

  if (near.empty()) {
    const Eigen::Index k = index_->nearest(x);
    ev.gradient = normals_.row(k).transpose();
    ev.value = ev.gradient.dot(x - points_.row(k).transpose());
    ev.fallback = true;
    return ev;
  }

  // Relative weights w_k = (u_k/u_max)⁴ = φ_k/φ_max; ψ_k = w_k / Σ w.
  double sum_w = 0.0, sum_wa = 0.0;
  std::vector<double> w(near.size()), a(near.size());
  for (std::size_t i = 0; i < near.size(); ++i) {
    const double q = near[i].u / u_max;
    const double q2 = q * q;
    w[i] = q2 * q2;
    a[i] = normals_.row(near[i].k).dot(x.transpose() - points_.row(near[i].k));
    sum_w += w[i];
    sum_wa += w[i] * a[i];
  }
  ev.value = sum_wa / sum_w;
  // ∇f = Σ ψ_k n_k + Σ (a_k − f) ψ_k ∇φ_k/φ_k,  ∇φ_k/φ_k = −8 (x − c_k) / (h² u_k).
  for (std::size_t i = 0; i < near.size(); ++i) {
    const double psi = w[i] / sum_w;
    if (psi == 0.0) continue;
    const Vec3 d = x - points_.row(near[i].k).transpose();
    ev.gradient += psi * normals_.row(near[i].k).transpose() +
                   (a[i] - ev.value) * psi * (-8.0 / (h2 * near[i].u)) * d;
  }
  return ev;
}

}  // namespace tightfit
