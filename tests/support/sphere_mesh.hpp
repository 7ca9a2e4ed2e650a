#pragma once
/// A sphere surface from the body generator, for the tests of the body layer.
#include "tightfit/body/generators.hpp"

namespace tightfit::test {

/// The generator's sphere of `radius` (m) around `center`, edges of about `edge` (m), its
/// vertices on the sphere itself (not fitted to a limit surface).
inline TriMesh sphere_mesh(double radius, const Vec3& center, double edge) {
  SphereParams p;
  p.radius = radius;
  p.center = center;
  p.edge_length = edge;
  p.fit_limit = false;
  return sphere_surface(p);
}

}  // namespace tightfit::test
