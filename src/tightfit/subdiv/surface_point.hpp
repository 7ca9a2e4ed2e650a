#pragma once
/// A point on the Loop limit surface of a body's control mesh, given by the control
/// face it lies in and barycentric-style coordinates (u, v) of that face:
/// corner 0 at (0,0), corner 1 at (1,0), corner 2 at (0,1); u ≥ 0, v ≥ 0, u + v ≤ 1.
namespace tightfit {

struct SurfacePoint {
  int face = -1;
  double u = 0.0;
  double v = 0.0;
};

}  // namespace tightfit
