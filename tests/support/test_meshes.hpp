#pragma once
/// Small closed meshes built in code, shared by the tests of several layers.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

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

/// The icosahedron split twice (edges halved, new vertices pushed onto the unit sphere):
/// 320 faces, edges of about 0.3.
inline TriMesh unit_icosphere() {
  TriMesh m = test::icosahedron();
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<int, int>, int> middle;
    std::vector<Vec3> v;
    for (int i = 0; i < m.num_vertices(); ++i) v.push_back(m.vertices.row(i).transpose());
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = middle.find(key); it != middle.end()) return it->second;
      v.push_back((v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)]).normalized());
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    Triangles faces(4 * m.num_faces(), 3);
    for (int f = 0; f < m.num_faces(); ++f) {
      const int a = m.faces(f, 0), b = m.faces(f, 1), c = m.faces(f, 2);
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      faces.row(4 * f) << a, ab, ca;
      faces.row(4 * f + 1) << ab, b, bc;
      faces.row(4 * f + 2) << ca, bc, c;
      faces.row(4 * f + 3) << ab, bc, ca;
    }
    m.faces = faces;
    m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
    for (size_t i = 0; i < v.size(); ++i)
      m.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  }
  return m;
}

}  // namespace tightfit::test
