#pragma once
/// A point on the Loop limit surface of a body's control mesh, given by the control
/// face it lies in and barycentric-style coordinates (u, v) of that face:
/// corner 0 at (0,0), corner 1 at (1,0), corner 2 at (0,1); u ≥ 0, v ≥ 0, u + v ≤ 1.
#include <string>
#include <vector>

#include "tightfit/common/error.hpp"

namespace tightfit {

struct SurfacePoint {
  int face = -1;
  double u = 0.0;
  double v = 0.0;
};

/// How far (in u, v) outside its face a surface point may lie from round-off.
inline constexpr double kSurfacePointTolerance = 1e-12;

/// True when `s` is a point of a surface of `num_faces` faces: its face exists and (u, v)
/// lies in the parameter triangle u, v ≥ 0, u + v ≤ 1 up to kSurfacePointTolerance
/// (false for non-finite coordinates).
inline bool is_surface_point(const SurfacePoint& s, int num_faces) {
  return s.face >= 0 && s.face < num_faces && s.u >= -kSurfacePointTolerance &&
         s.v >= -kSurfacePointTolerance && s.u + s.v <= 1.0 + kSurfacePointTolerance;
}

/// Throws InputError(source) naming the first of `points` that is not a surface point of
/// a surface of `num_faces` faces (is_surface_point), at "`path`/i".
inline void check_surface_points(const std::vector<SurfacePoint>& points, int num_faces,
                                 const std::string& source, const std::string& path) {
  for (size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& q = points[i];
    if (is_surface_point(q, num_faces)) continue;
    const std::string at = path + "/" + std::to_string(i);
    if (q.face < 0 || q.face >= num_faces)
      throw InputError(source, at + "/0: face " + std::to_string(q.face) +
                                   " does not exist (the body surface has " +
                                   std::to_string(num_faces) + " faces)");
    throw InputError(source, at + ": (u, v) = (" + std::to_string(q.u) + ", " +
                                 std::to_string(q.v) + ") is outside the face");
  }
}

}  // namespace tightfit
