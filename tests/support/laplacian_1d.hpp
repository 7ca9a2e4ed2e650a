#pragma once
/// The n×n 1D Laplacian tridiag(−1, 2 + shift, −1): a small SPD test matrix (positive
/// definite for shift > −4 sin²(π/(2(n+1)))), shared by the linear-solver tests.
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit::test {

inline SparseMatrix laplacian_1d(int n, double shift) {
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace tightfit::test
