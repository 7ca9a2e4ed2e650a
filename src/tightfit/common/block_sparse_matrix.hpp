#pragma once
/// A sparse matrix of 3×3 blocks, vertex by vertex (rows and columns 3v, 3v+1, 3v+2 of
/// vertex v), assembled from dense element matrices (ElementMatrices) and scalar
/// triplets such as Energy::add_hessian writes, held in block-compressed-column form.
/// Where the elements and triplets write is analysed once (the layout); an assembly
/// whose elements couple the same vertices and whose triplets stand at the same
/// positions as the layout's is one pass adding each value to its block entry (no
/// sort). Each block entry sums its terms in one fixed order (element parts in order,
/// elements in order, then the triplets in order), so the values do not depend on the
/// thread count. Energies write the same positions at every state (zeros included), so
/// the layout of an energy's Hessian is made once per mesh.
#include <cstdint>
#include <memory>
#include <vector>

#include "tightfit/common/element_matrices.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// Where the element matrices of one ElementMatrices go.
struct ElementBlocks {
  int vertices_per_element = 0;
  std::vector<int> vertices;  ///< the element vertex ids (the check)
  /// Per element e and vertex pair (row vertex a, column vertex b), at k²·e + k·b + a:
  /// the block that the element matrix's 3×3 block (a, b) adds to.
  std::vector<int> blocks;
};

/// Where the element matrices and triplets of an assembly go: the block pattern, the
/// block of each element block and the block entry of each triplet.
struct BlockLayout {
  int num_vertices = 0;
  std::vector<int> column_start;        ///< num_vertices + 1 offsets into `rows`
  std::vector<int> rows;                ///< block row of each block, ascending per column
  std::vector<ElementBlocks> elements;  ///< one per ElementMatrices of the assembly
  std::vector<std::int64_t> positions;  ///< per triplet: row · 3n + column (the check)
  std::vector<int> entry;               ///< per triplet: 9 · block + 3 · (column % 3) + row % 3
};

class BlockSparseMatrix3 {
 public:
  BlockSparseMatrix3() = default;

  /// Σ triplets (duplicates summed) as a (3·num_vertices)² matrix. `hint`: the layout of
  /// an earlier assembly (layout()), used when these triplets stand at its positions;
  /// otherwise a new layout is made. Throws std::invalid_argument for an index outside
  /// the matrix.
  static BlockSparseMatrix3 from_triplets(const std::vector<Triplet>& triplets, int num_vertices,
                                          std::shared_ptr<const BlockLayout> hint = nullptr);
  /// Σ element matrices + Σ triplets as a (3·num_vertices)² matrix; the element blocks
  /// are summed on thread_count() threads (each owns a range of block columns). `hint`
  /// as for from_triplets: used when the elements couple the same vertices and the
  /// triplets stand at the same positions. Throws std::invalid_argument for an index
  /// outside the matrix.
  static BlockSparseMatrix3 assemble(const std::vector<ElementMatrices>& elements,
                                     const std::vector<Triplet>& triplets, int num_vertices,
                                     std::shared_ptr<const BlockLayout> hint = nullptr);

  const std::shared_ptr<const BlockLayout>& layout() const { return layout_; }
  int num_vertices() const { return layout_ ? layout_->num_vertices : 0; }
  /// Blocks of block column c are k ∈ [column_begin(c), column_end(c)), in block row
  /// row(k) ascending; block(k) points at its 9 values, column-major.
  int column_begin(int c) const { return layout_->column_start[c]; }
  int column_end(int c) const { return layout_->column_start[c + 1]; }
  int row(int k) const { return layout_->rows[k]; }
  const double* block(int k) const { return values_.data() + 9 * static_cast<std::size_t>(k); }

 private:
  std::shared_ptr<const BlockLayout> layout_;
  std::vector<double> values_;  // 9 per block, column-major
};

}  // namespace tightfit
