#include <opensubdiv/bfr/surface.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/subdiv/limit_surface.hpp"
#include "tightfit/subdiv/limit_surface_impl.hpp"

namespace tightfit {

void LimitSurface::run_self_test() {
  const Impl& m = *impl_;
  // Compare OpenSubdiv's raw second-derivative stencils with central differences of its
  // first-derivative stencils, inside a rotated sub-triangle (the depth-1 middle
  // triangle: a regular patch for every irregular face) and inside a non-rotated one.
  std::vector<int> irregular_faces;
  for (int f = 0; f < num_faces(); ++f) {
    if (m.irregular[static_cast<std::size_t>(f)]) irregular_faces.push_back(f);
  }
  if (irregular_faces.empty()) return;
  const int max_tested = 32;
  const int stride = std::max(1, static_cast<int>(irregular_faces.size()) / max_tested);
  const double h = 1e-5;
  const double tolerance = 1e-5;
  int buggy = 0;
  int correct = 0;
  const int n_max = m.max_control_points;
  std::vector<double> c(6 * static_cast<std::size_t>(n_max)),
      a(6 * static_cast<std::size_t>(n_max)), z(6 * static_cast<std::size_t>(n_max));
  // Relative errors of (duu, duv, dvv) and of their negatives against central differences.
  auto errors = [&](int f, double u, double v, double& plain, double& flipped) {
    const OpenSubdiv::Bfr::Surface<double>& s = m.surfaces[static_cast<std::size_t>(f)];
    const int n = s.GetNumControlPoints();
    auto eval = [&](double uu, double vv, std::vector<double>& w) {
      const double uv[2] = {uu, vv};
      s.EvaluateStencil(uv, w.data(), w.data() + n, w.data() + 2 * n, w.data() + 3 * n,
                        w.data() + 4 * n, w.data() + 5 * n);
    };
    eval(u, v, c);
    double e_plain = 0.0, e_flip = 0.0, norm = 0.0;
    // duu and duv from d/du of (du, dv); dvv from d/dv of dv.
    eval(u + h, v, a);
    eval(u - h, v, z);
    for (int k = 0; k < n; ++k) {
      const double fd_uu =
          (a[static_cast<std::size_t>(n + k)] - z[static_cast<std::size_t>(n + k)]) / (2 * h);
      const double fd_uv =
          (a[static_cast<std::size_t>(2 * n + k)] - z[static_cast<std::size_t>(2 * n + k)]) /
          (2 * h);
      const double uu = c[static_cast<std::size_t>(3 * n + k)],
                   uvw = c[static_cast<std::size_t>(4 * n + k)];
      e_plain += (uu - fd_uu) * (uu - fd_uu) + (uvw - fd_uv) * (uvw - fd_uv);
      e_flip += (uu + fd_uu) * (uu + fd_uu) + (uvw + fd_uv) * (uvw + fd_uv);
      norm += fd_uu * fd_uu + fd_uv * fd_uv;
    }
    eval(u, v + h, a);
    eval(u, v - h, z);
    for (int k = 0; k < n; ++k) {
      const double fd_vv =
          (a[static_cast<std::size_t>(2 * n + k)] - z[static_cast<std::size_t>(2 * n + k)]) /
          (2 * h);
      const double vv = c[static_cast<std::size_t>(5 * n + k)];
      e_plain += (vv - fd_vv) * (vv - fd_vv);
      e_flip += (vv + fd_vv) * (vv + fd_vv);
      norm += fd_vv * fd_vv;
    }
    plain = std::sqrt(e_plain / norm);
    flipped = std::sqrt(e_flip / norm);
  };
  auto fail = [](int f, double u, double v, double plain, double flipped) {
    throw SolverError("LimitSurface self-test: OpenSubdiv second derivatives on face " +
                      std::to_string(f) + " at (" + std::to_string(u) + ", " + std::to_string(v) +
                      ") match neither finite differences nor their negatives (relative errors " +
                      std::to_string(plain) + ", " + std::to_string(flipped) + ")");
  };
  for (std::size_t q = 0; q < irregular_faces.size(); q += static_cast<std::size_t>(stride)) {
    const int f = irregular_faces[q];
    double plain = 0.0, flipped = 0.0;
    for (const auto& uv : {Vec2(0.3, 0.3), Vec2(0.2, 0.35)}) {
      errors(f, uv[0], uv[1], plain, flipped);
      if (plain < tolerance) {
        ++correct;
      } else if (flipped < tolerance) {
        ++buggy;
      } else {
        fail(f, uv[0], uv[1], plain, flipped);
      }
    }
    // A non-rotated regular sub-patch: the depth-1 corner-0 triangle or, when corner 0
    // is extraordinary, the depth-2 triangle of that corner towards corner 1.
    const bool gregory = (m.ev_corners[static_cast<std::size_t>(f)] & 1u) && m.patch_tree_depth < 2;
    if (!gregory) {
      errors(f, 0.35, 0.05, plain, flipped);
      if (plain >= tolerance) fail(f, 0.35, 0.05, plain, flipped);
    }
  }
  if (buggy > 0 && correct > 0) {
    throw SolverError(
        "LimitSurface self-test: OpenSubdiv second derivatives have the wrong sign on " +
        std::to_string(buggy) + " of " + std::to_string(buggy + correct) +
        " rotated sub-triangles; expected all or none");
  }
  fix_second_derivatives_ = buggy > 0;
}

}  // namespace tightfit
