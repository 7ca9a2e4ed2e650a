#include "tightfit/common/block_sparse_matrix.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

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

/// Sums the triplets into `values` by `layout`; false when a triplet does not stand
/// at the layout's position (the values are then unusable).
bool scatter(const BlockLayout& layout, const std::vector<Triplet>& triplets,
             std::vector<double>& values) {
  if (triplets.size() != layout.positions.size()) return false;
  const std::int64_t size = 3 * static_cast<std::int64_t>(layout.num_vertices);
  values.assign(9 * layout.rows.size(), 0.0);
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
  BlockSparseMatrix3 m;
  if (hint && hint->num_vertices == num_vertices && scatter(*hint, triplets, m.values_)) {
    m.layout_ = std::move(hint);
    return m;
  }
  m.layout_ = make_layout(triplets, num_vertices);
  scatter(*m.layout_, triplets, m.values_);
  return m;
}

}  // namespace tightfit
