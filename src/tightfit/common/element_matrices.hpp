#pragma once
/// Dense Hessians of the elements of one energy, kept element by element instead of as
/// scalar triplets: element e couples the k vertices vertices()[k·e … k·e + k − 1]
/// (k = vertices_per_element(), 3 DOFs per vertex), and matrix(e) points at its
/// (3k)×(3k) matrix, column-major, rows and columns ordered vertex by vertex (DOF 3a + i
/// is component i of the element's vertex a). BlockSparseMatrix3::assemble sums them
/// block by block, which reads a ninth of what the same Hessian as triplets takes.
#include <cstdint>
#include <memory>
#include <vector>

namespace tightfit {

class ElementMatrices {
 public:
  /// Room for one matrix per element of `vertices` (k ids per element). The values
  /// start uninitialized: every matrix is to be written whole. Throws
  /// std::invalid_argument for k < 1 or a vertex count that is not a multiple of k.
  ElementMatrices(int vertices_per_element, std::vector<int> vertices);

  int vertices_per_element() const { return vertices_per_element_; }
  /// Rows (= columns) of one element matrix: 3k.
  int matrix_size() const { return 3 * vertices_per_element_; }
  std::int64_t num_elements() const { return num_elements_; }
  /// The element vertex ids, k per element.
  const std::vector<int>& vertices() const { return vertices_; }
  /// The (3k)² values of element e's matrix, column-major.
  double* matrix(std::int64_t e) { return values_.get() + e * matrix_values(); }
  const double* matrix(std::int64_t e) const { return values_.get() + e * matrix_values(); }

 private:
  std::int64_t matrix_values() const { return std::int64_t{matrix_size()} * matrix_size(); }

  int vertices_per_element_ = 0;
  std::int64_t num_elements_ = 0;
  std::vector<int> vertices_;
  std::unique_ptr<double[]> values_;
};

}  // namespace tightfit
