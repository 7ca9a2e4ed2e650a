#include "tightfit/common/block_sparse_matrix.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "tightfit/common/parallel.hpp"

namespace tightfit {
namespace {

std::int64_t position_of(const Triplet& t, std::int64_t size) {
  return static_cast<std::int64_t>(t.row()) * size + t.col();
}

/// The layout of `triplets`: the block pattern by a counting sort over block columns.
std::shared_ptr<const BlockLayout> make_layout(const std::vector<Triplet>& triplets,
                                               int num_vertices) {
  auto layout = std::make_shared<BlockLayout>();
  layout->num_vertices = num_vertices;
  const std::int64_t size = 3 * static_cast<std::int64_t>(num_vertices);
  const std::size_t count = triplets.size();
  if (count > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("BlockSparseMatrix3: too many triplets");
  layout->positions.resize(count);
  std::vector<int> by_column_start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (std::size_t t = 0; t < count; ++t) {
    const Triplet& e = triplets[t];
    if (e.row() < 0 || e.col() < 0 || e.row() >= size || e.col() >= size)
      throw std::invalid_argument("BlockSparseMatrix3: triplet (" + std::to_string(e.row()) + ", " +
                                  std::to_string(e.col()) + ") outside a " + std::to_string(size) +
                                  "² matrix");
    layout->positions[t] = position_of(e, size);
    ++by_column_start[static_cast<std::size_t>(e.col() / 3) + 1];
  }
  for (int c = 0; c < num_vertices; ++c) by_column_start[c + 1] += by_column_start[c];
  std::vector<int> by_column(count);
  {
    std::vector<int> next(by_column_start.begin(), by_column_start.end() - 1);
    for (std::size_t t = 0; t < count; ++t)
      by_column[next[triplets[t].col() / 3]++] = static_cast<int>(t);
  }
  // Block pattern, column by column; the block of each triplet.
  std::vector<int> block_of_row(static_cast<std::size_t>(num_vertices), -1);
  layout->entry.resize(count);
  layout->column_start.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (int c = 0; c < num_vertices; ++c) {
    const int begin = by_column_start[c], end = by_column_start[c + 1];
    const std::size_t first = layout->rows.size();
    for (int k = begin; k < end; ++k) {
      const int r = triplets[by_column[k]].row() / 3;
      if (block_of_row[r] < 0) {
        block_of_row[r] = 0;
        layout->rows.push_back(r);
      }
    }
    std::sort(layout->rows.begin() + static_cast<std::ptrdiff_t>(first), layout->rows.end());
    for (std::size_t k = first; k < layout->rows.size(); ++k)
      block_of_row[layout->rows[k]] = static_cast<int>(k);
    for (int k = begin; k < end; ++k) {
      const Triplet& e = triplets[by_column[k]];
      layout->entry[by_column[k]] = 9 * block_of_row[e.row() / 3] + 3 * (e.col() % 3) + e.row() % 3;
    }
    for (std::size_t k = first; k < layout->rows.size(); ++k) block_of_row[layout->rows[k]] = -1;
    layout->column_start[c + 1] = static_cast<int>(layout->rows.size());
  }
  return layout;
}

/// The layout of element matrices followed by triplets: the triplets' layout with one
/// stand-in triplet per element block (at the block's first entry) in front.
std::shared_ptr<const BlockLayout> make_layout(const std::vector<ElementMatrices>& elements,
                                               const std::vector<Triplet>& triplets,
                                               int num_vertices) {
  if (elements.empty()) return make_layout(triplets, num_vertices);
  std::vector<Triplet> all;
  for (const ElementMatrices& part : elements) {
    const int k = part.vertices_per_element();
    for (std::int64_t e = 0; e < part.num_elements(); ++e) {
      const int* ids = part.vertices().data() + k * e;
      for (int a = 0; a < k; ++a)
        if (ids[a] < 0 || ids[a] >= num_vertices)
          throw std::invalid_argument("BlockSparseMatrix3: element " + std::to_string(e) +
                                      " has vertex " + std::to_string(ids[a]) + " outside [0, " +
                                      std::to_string(num_vertices) + ")");
      for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a) all.emplace_back(3 * ids[a], 3 * ids[b], 0.0);
    }
  }
  const std::size_t stand_ins = all.size();
  all.insert(all.end(), triplets.begin(), triplets.end());
  auto layout = std::make_shared<BlockLayout>(*make_layout(all, num_vertices));
  std::size_t next = 0;
  for (const ElementMatrices& part : elements) {
    ElementBlocks& blocks = layout->elements.emplace_back();
    blocks.vertices_per_element = part.vertices_per_element();
    blocks.vertices = part.vertices();
    const int k = part.vertices_per_element();
    blocks.blocks.resize(static_cast<std::size_t>(part.num_elements() * k * k));
    for (int& block : blocks.blocks) block = layout->entry[next++] / 9;
  }
  layout->positions.erase(layout->positions.begin(),
                          layout->positions.begin() + static_cast<std::ptrdiff_t>(stand_ins));
  layout->entry.erase(layout->entry.begin(),
                      layout->entry.begin() + static_cast<std::ptrdiff_t>(stand_ins));
  return layout;
}

/// True when `elements` couple the vertices that `layout` was made for.
bool same_elements(const BlockLayout& layout, const std::vector<ElementMatrices>& elements) {
  if (layout.elements.size() != elements.size()) return false;
  for (std::size_t p = 0; p < elements.size(); ++p)
    if (layout.elements[p].vertices_per_element != elements[p].vertices_per_element() ||
        layout.elements[p].vertices != elements[p].vertices())
      return false;
  return true;
}

/// Adds the element blocks whose block column (vertex) lies in [first_column,
/// end_column) to `values`, element by element.
void add_element_blocks(const ElementBlocks& layout, const ElementMatrices& part, int first_column,
                        int end_column, double* values) {
  const int k = part.vertices_per_element();
  const int n = part.matrix_size();
  for (std::int64_t e = 0; e < part.num_elements(); ++e) {
    const int* ids = layout.vertices.data() + k * e;
    const int* blocks = layout.blocks.data() + k * k * e;
    const double* local = part.matrix(e);
    for (int b = 0; b < k; ++b) {
      if (ids[b] < first_column || ids[b] >= end_column) continue;
      for (int a = 0; a < k; ++a) {
        double* block = values + 9 * static_cast<std::size_t>(blocks[k * b + a]);
        for (int j = 0; j < 3; ++j) {
          const double* column = local + static_cast<std::ptrdiff_t>(3 * b + j) * n + 3 * a;
          block[3 * j] += column[0];
          block[3 * j + 1] += column[1];
          block[3 * j + 2] += column[2];
        }
      }
    }
  }
}

/// Sums the element matrices into `values` by `layout`, on thread_count() threads, each
/// owning a range of block columns with about the same number of blocks.
void scatter_elements(const BlockLayout& layout, const std::vector<ElementMatrices>& elements,
                      std::vector<double>& values) {
  if (elements.empty()) return;
  const int n = layout.num_vertices;
  const int threads = std::max(1, std::min(thread_count(), n));
  std::vector<int> first_column(static_cast<std::size_t>(threads) + 1, n);
  first_column[0] = 0;
  const int blocks = layout.column_start.back();
  for (int t = 1; t < threads; ++t)
    first_column[t] = static_cast<int>(
        std::lower_bound(layout.column_start.begin(), layout.column_start.end() - 1,
                         static_cast<int>(static_cast<std::int64_t>(blocks) * t / threads)) -
        layout.column_start.begin());
  run_on_threads(threads, [&](int t) {
    for (std::size_t p = 0; p < elements.size(); ++p)
      add_element_blocks(layout.elements[p], elements[p], first_column[t], first_column[t + 1],
                         values.data());
  });
}

/// Adds the triplets to `values` by `layout`; false when a triplet does not stand at
/// the layout's position (the values are then unusable).
bool scatter(const BlockLayout& layout, const std::vector<Triplet>& triplets,
             std::vector<double>& values) {
  if (triplets.size() != layout.positions.size()) return false;
  const std::int64_t size = 3 * static_cast<std::int64_t>(layout.num_vertices);
  for (std::size_t t = 0; t < triplets.size(); ++t) {
    const Triplet& e = triplets[t];
    if (position_of(e, size) != layout.positions[t]) return false;
    values[static_cast<std::size_t>(layout.entry[t])] += e.value();
  }
  return true;
}

}  // namespace

BlockSparseMatrix3 BlockSparseMatrix3::from_triplets(const std::vector<Triplet>& triplets,
                                                     int num_vertices,
                                                     std::shared_ptr<const BlockLayout> hint) {
  return assemble({}, triplets, num_vertices, std::move(hint));
}

BlockSparseMatrix3 BlockSparseMatrix3::assemble(const std::vector<ElementMatrices>& elements,
                                                const std::vector<Triplet>& triplets,
                                                int num_vertices,
                                                std::shared_ptr<const BlockLayout> hint) {
  BlockSparseMatrix3 m;
  if (hint && hint->num_vertices == num_vertices && same_elements(*hint, elements)) {
    m.values_.assign(9 * hint->rows.size(), 0.0);
    scatter_elements(*hint, elements, m.values_);
    if (scatter(*hint, triplets, m.values_)) {
      m.layout_ = std::move(hint);
      return m;
    }
  }
  m.layout_ = make_layout(elements, triplets, num_vertices);
  m.values_.assign(9 * m.layout_->rows.size(), 0.0);
  scatter_elements(*m.layout_, elements, m.values_);
  scatter(*m.layout_, triplets, m.values_);
  return m;
}

}  // namespace tightfit
