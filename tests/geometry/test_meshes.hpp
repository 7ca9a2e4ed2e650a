#pragma once
/// Small meshes built in code for the geometry tests (the icosahedron is shared:
/// support/test_meshes.hpp).
#include <cmath>

#include "support/test_meshes.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit::test {

/// Open strip of `n` quads (2n triangles) in the z = 0 plane, normals +z.
/// Bottom row vertices 0..n at y = 0, top row n+1..2n+1 at y = 1.
inline TriMesh strip(int n) {
  TriMesh m;
  m.vertices.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    m.vertices.row(i) << i, 0, 0;
    m.vertices.row(n + 1 + i) << i, 1, 0;
  }
  m.faces.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int a = i, b = i + 1, c = n + 2 + i, d = n + 1 + i;
    m.faces.row(2 * i) << a, b, c;
    m.faces.row(2 * i + 1) << a, c, d;
  }
  return m;
}

/// Axis-aligned unit cube [0,1]^3 as 12 outward triangles.
inline TriMesh cube() {
  TriMesh m;
  m.vertices.resize(8, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  m.faces.resize(12, 3);
  m.faces << 0, 2, 1, 0, 3, 2,  // z = 0
      4, 5, 6, 4, 6, 7,         // z = 1
      0, 1, 5, 0, 5, 4,         // y = 0
      3, 7, 6, 3, 6, 2,         // y = 1
      0, 4, 7, 0, 7, 3,         // x = 0
      1, 2, 6, 1, 6, 5;         // x = 1
  return m;
}

}  // namespace tightfit::test
