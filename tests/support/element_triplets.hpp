#pragma once
/// Element matrices (ElementMatrices) as scalar triplets over the global DOFs: the
/// reference that BlockSparseMatrix3::assemble and Energy::add_element_hessians are
/// checked against.
#include <vector>

#include "tightfit/common/element_matrices.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit::test {

/// Appends every entry of every element matrix of `m` at its global row and column
/// (3 · vertex + component).
inline void append_element_triplets(const ElementMatrices& m, std::vector<Triplet>& t) {
  const int k = m.vertices_per_element(), size = m.matrix_size();
  for (std::int64_t e = 0; e < m.num_elements(); ++e)
    for (int c = 0; c < size; ++c)
      for (int r = 0; r < size; ++r)
        t.emplace_back(3 * m.vertices()[k * e + r / 3] + r % 3,
                       3 * m.vertices()[k * e + c / 3] + c % 3, m.matrix(e)[c * size + r]);
}

}  // namespace tightfit::test
