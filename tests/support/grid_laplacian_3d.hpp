#pragma once
/// A 3D grid Laplacian: a sparse SPD test matrix large enough for a supernodal factor,
/// shared by the linear-solver tests.
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit::test {

/// The 7-point Laplacian of an m×m×m grid plus `shift`·I: large enough for CHOLMOD to
/// choose a supernodal factor.
inline SparseMatrix grid_laplacian_3d(int m, double shift) {
  std::vector<Triplet> t;
  auto id = [m](int i, int j, int k) { return (i * m + j) * m + k; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        t.emplace_back(id(i, j, k), id(i, j, k), 6.0 + shift);
        const int here = id(i, j, k);
        for (const int there : {i + 1 < m ? id(i + 1, j, k) : -1, j + 1 < m ? id(i, j + 1, k) : -1,
                                k + 1 < m ? id(i, j, k + 1) : -1}) {
          if (there < 0) continue;
          t.emplace_back(here, there, -1.0);
          t.emplace_back(there, here, -1.0);
        }
      }
  SparseMatrix A(m * m * m, m * m * m);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace tightfit::test
