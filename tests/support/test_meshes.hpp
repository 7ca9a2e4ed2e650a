#pragma once
/// Small closed meshes built in code, shared by the tests of several layers.
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

}  // namespace tightfit::test
