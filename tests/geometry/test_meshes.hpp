#pragma once
/// Small meshes built in code for the geometry tests.
#include <cmath>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit::test {

/// Regular icosahedron with circumradius 1, outward (counter-clockwise) faces.
inline TriMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriMesh m;
  m.vertices.resize(12, 3);
  m.vertices << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0,  //
      0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t,            //
      t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1;
  m.vertices /= std::sqrt(1.0 + t * t);
  m.faces.resize(20, 3);
  m.faces << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11,  //
      1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,         //
      3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9,             //
      4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1;
  return m;
}

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
