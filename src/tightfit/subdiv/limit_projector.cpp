#include "tightfit/subdiv/limit_projector.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace tightfit {

SurfacePoint refine_closest_point(const LimitSurface& surface, const Points3& control,
                                  const Vec3& p, SurfacePoint start) {
  const int max_iterations = 100;
  const int max_halvings = 40;
  const double max_step = 0.5;  // in (u,v): half a face
  SurfacePoint s = start;
  LimitFrame fr = surface.evaluate(s, control);
  Vec3 r = fr.x - p;
  double energy = r.squaredNorm();
  const double length = std::sqrt(fr.xu.squaredNorm() + fr.xv.squaredNorm());
  for (int it = 0; it < max_iterations; ++it) {
    Mat32 T;
    T << fr.xu, fr.xv;
    const Vec2 g = T.transpose() * r;
    const Mat2 G = T.transpose() * T;
    Mat2 H = G;
    H(0, 0) += r.dot(fr.xuu);
    H(0, 1) += r.dot(fr.xuv);
    H(1, 0) += r.dot(fr.xuv);
    H(1, 1) += r.dot(fr.xvv);
    const double scale = G.trace();
    Vec2 directions[2];
    int num_directions = 0;
    const Eigen::SelfAdjointEigenSolver<Mat2> eig(H);
    if (eig.eigenvalues()[0] > 1e-8 * scale) directions[num_directions++] = -H.ldlt().solve(g);
    const Mat2 Gs = G + (1e-12 * scale + 1e-300) * Mat2::Identity();
    directions[num_directions++] = -Gs.ldlt().solve(g);
    bool accepted = false;
    bool converged = false;
    for (int q = 0; q < num_directions && !accepted; ++q) {
      Vec2 step = directions[q];
      if (!step.allFinite()) continue;
      const double inf = step.cwiseAbs().maxCoeff();
      if (inf > max_step) step *= max_step / inf;
      if ((T * step).norm() <= 1e-13 * length) {
        converged = true;
        break;
      }
      double alpha = 1.0;
      for (int k = 0; k <= max_halvings; ++k, alpha *= 0.5) {
        const LimitSurface::Walk w = surface.walk(s, alpha * step);
        const Vec3 x = surface.position(w.end, control);
        const double e = (x - p).squaredNorm();
        if (e < energy) {
          s = w.end;
          energy = e;
          accepted = true;
          break;
        }
      }
    }
    if (converged || !accepted) break;
    fr = surface.evaluate(s, control);
    r = fr.x - p;
  }
  return s;
}

LimitProjector::LimitProjector(const LimitSurface& surface, const Points3& control,
                               int samples_per_edge)
    : surface_(surface), control_(control) {
  if (control.rows() != surface.num_control_vertices()) {
    throw std::invalid_argument("LimitProjector: control has " + std::to_string(control.rows()) +
                                " rows, expected " +
                                std::to_string(surface.num_control_vertices()));
  }
  if (samples_per_edge < 1)
    throw std::invalid_argument("LimitProjector: samples_per_edge must be ≥ 1");
  const int n = samples_per_edge;
  const double inv = 1.0 / n;
  for (int f = 0; f < surface.num_faces(); ++f) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        samples_.push_back({f, (i + 1.0 / 3.0) * inv, (j + 1.0 / 3.0) * inv});
        if (i + j + 1 < n) samples_.push_back({f, (i + 2.0 / 3.0) * inv, (j + 2.0 / 3.0) * inv});
      }
    }
  }
  Points3 sample_positions(static_cast<Eigen::Index>(samples_.size()), 3);
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    sample_positions.row(static_cast<Eigen::Index>(k)) =
        surface.position(samples_[k], control_).transpose();
  }
  sample_index_ = std::make_unique<PointCloudIndex>(std::move(sample_positions));
}

LimitProjector::~LimitProjector() = default;

SurfacePoint LimitProjector::nearest_sample(const Vec3& p) const {
  return samples_[static_cast<std::size_t>(sample_index_->nearest(p))];
}

SurfacePoint LimitProjector::project(const Vec3& p) const {
  return refine_closest_point(surface_, control_, p, nearest_sample(p));
}

}  // namespace tightfit
