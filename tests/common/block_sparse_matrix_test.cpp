#include "tightfit/common/block_sparse_matrix.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "support/element_triplets.hpp"
#include "tightfit/common/parallel.hpp"

namespace tightfit::block_sparse_matrix_test {

/// Random triplets over `n` vertices: some blocks written several times, some entries
/// only partly (not every block holds all nine entries).
std::vector<Triplet> random_triplets(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> index(0, 3 * n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Triplet> t;
  for (int k = 0; k < 40 * n; ++k) t.emplace_back(index(rng), index(rng), value(rng));
  return t;
}

MatX dense(const BlockSparseMatrix3& m) {
  const int n = m.num_vertices();
  MatX out = MatX::Zero(3 * n, 3 * n);
  for (int c = 0; c < n; ++c)
    for (int k = m.column_begin(c); k < m.column_end(c); ++k) {
      if (k > m.column_begin(c)) {
        EXPECT_LT(m.row(k - 1), m.row(k));  // ascending rows
      }
      out.block<3, 3>(3 * m.row(k), 3 * c) += Eigen::Map<const Mat3>(m.block(k));
    }
  return out;
}

MatX reference(const std::vector<Triplet>& t, int n) {
  SparseMatrix s(3 * n, 3 * n);
  s.setFromTriplets(t.begin(), t.end());
  return MatX(s);
}

TEST(BlockSparseMatrix3, SumsTheTripletsLikeSetFromTriplets) {
  const int n = 17;
  const std::vector<Triplet> t = random_triplets(n, 4);
  const BlockSparseMatrix3 m = BlockSparseMatrix3::from_triplets(t, n);
  EXPECT_EQ(m.num_vertices(), n);
  EXPECT_LT((dense(m) - reference(t, n)).norm(), 1e-14);
}

TEST(BlockSparseMatrix3, ReusesTheLayoutOfTripletsAtTheSamePositions) {
  const int n = 11;
  std::vector<Triplet> t = random_triplets(n, 7);
  const BlockSparseMatrix3 first = BlockSparseMatrix3::from_triplets(t, n);
  for (Triplet& e : t) e = Triplet(e.row(), e.col(), 2.0 * e.value() + 1.0);
  const BlockSparseMatrix3 again = BlockSparseMatrix3::from_triplets(t, n, first.layout());
  EXPECT_EQ(again.layout(), first.layout());
  EXPECT_LT((dense(again) - reference(t, n)).norm(), 1e-13);
}

TEST(BlockSparseMatrix3, MakesANewLayoutWhenThePositionsChange) {
  const int n = 11;
  std::vector<Triplet> t = random_triplets(n, 9);
  const BlockSparseMatrix3 first = BlockSparseMatrix3::from_triplets(t, n);
  // One triplet moved (same count), then one more triplet: both need a new layout.
  std::vector<Triplet> moved = t;
  moved[5] = Triplet((t[5].row() + 4) % (3 * n), t[5].col(), t[5].value());
  const BlockSparseMatrix3 m1 = BlockSparseMatrix3::from_triplets(moved, n, first.layout());
  EXPECT_NE(m1.layout(), first.layout());
  EXPECT_LT((dense(m1) - reference(moved, n)).norm(), 1e-14);
  std::vector<Triplet> longer = t;
  longer.emplace_back(0, 3 * n - 1, 5.0);
  const BlockSparseMatrix3 m2 = BlockSparseMatrix3::from_triplets(longer, n, first.layout());
  EXPECT_NE(m2.layout(), first.layout());
  EXPECT_LT((dense(m2) - reference(longer, n)).norm(), 1e-14);
  // A layout for another size is not used either.
  const BlockSparseMatrix3 m3 = BlockSparseMatrix3::from_triplets(t, n + 1, first.layout());
  EXPECT_EQ(m3.num_vertices(), n + 1);
}

/// Random element matrices of k vertices each over `n` vertices; element 0 repeats a
/// vertex (its blocks add twice to the same block).
ElementMatrices random_elements(int k, int count, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> vertex(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<int> ids(static_cast<std::size_t>(k * count));
  for (int& v : ids) v = vertex(rng);
  if (k > 1) ids[1] = ids[0];
  ElementMatrices m(k, ids);
  const int size = 9 * k * k;
  for (int e = 0; e < count; ++e)
    for (int i = 0; i < size; ++i) m.matrix(e)[i] = value(rng);
  return m;
}

TEST(BlockSparseMatrix3, SumsElementMatricesAndTripletsLikeSetFromTriplets) {
  const int n = 23;
  std::vector<ElementMatrices> elements;
  elements.push_back(random_elements(4, 30, n, 1));
  elements.push_back(random_elements(2, 12, n, 2));
  const std::vector<Triplet> t = random_triplets(n, 3);
  std::vector<Triplet> all;
  for (const ElementMatrices& m : elements) test::append_element_triplets(m, all);
  all.insert(all.end(), t.begin(), t.end());
  const BlockSparseMatrix3 m = BlockSparseMatrix3::assemble(elements, t, n);
  EXPECT_LT((dense(m) - reference(all, n)).norm(), 1e-13);
  // Same elements and triplet positions, new values: the layout is reused.
  for (ElementMatrices& part : elements)
    for (std::int64_t e = 0; e < part.num_elements(); ++e) part.matrix(e)[0] += 1.0;
  all.clear();
  for (const ElementMatrices& part : elements) test::append_element_triplets(part, all);
  all.insert(all.end(), t.begin(), t.end());
  const BlockSparseMatrix3 again = BlockSparseMatrix3::assemble(elements, t, n, m.layout());
  EXPECT_EQ(again.layout(), m.layout());
  EXPECT_LT((dense(again) - reference(all, n)).norm(), 1e-13);
}

TEST(BlockSparseMatrix3, MakesANewLayoutWhenTheElementsChange) {
  const int n = 15;
  std::vector<ElementMatrices> elements;
  elements.push_back(random_elements(3, 20, n, 5));
  const BlockSparseMatrix3 first = BlockSparseMatrix3::assemble(elements, {}, n);
  // One element on other vertices (an element of the first layout is gone).
  std::vector<int> ids = elements[0].vertices();
  ids[7] = (ids[7] + 5) % n;
  std::vector<ElementMatrices> moved;
  moved.push_back(ElementMatrices(3, ids));
  for (std::int64_t e = 0; e < moved[0].num_elements(); ++e)
    std::copy_n(elements[0].matrix(e), 81, moved[0].matrix(e));
  std::vector<Triplet> all;
  test::append_element_triplets(moved[0], all);
  const BlockSparseMatrix3 m = BlockSparseMatrix3::assemble(moved, {}, n, first.layout());
  EXPECT_NE(m.layout(), first.layout());
  EXPECT_LT((dense(m) - reference(all, n)).norm(), 1e-13);
  // The same elements as triplets only: not the elements' layout either.
  const BlockSparseMatrix3 as_triplets = BlockSparseMatrix3::from_triplets(all, n, m.layout());
  EXPECT_NE(as_triplets.layout(), m.layout());
  EXPECT_LT((dense(as_triplets) - dense(m)).norm(), 1e-13);
}

TEST(BlockSparseMatrix3, ElementAssemblyIsTheSameForEveryThreadCount) {
  const int n = 400;
  std::vector<ElementMatrices> elements;
  elements.push_back(random_elements(4, 2000, n, 8));
  const int threads = thread_count();
  set_thread_count(1);
  const MatX one = dense(BlockSparseMatrix3::assemble(elements, {}, n));
  set_thread_count(2);
  const MatX two = dense(BlockSparseMatrix3::assemble(elements, {}, n));
  set_thread_count(threads);
  EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BlockSparseMatrix3, RejectsAnElementVertexOutsideTheMatrix) {
  std::vector<ElementMatrices> elements;
  elements.push_back(ElementMatrices(2, {0, 3}));
  std::fill_n(elements[0].matrix(0), 36, 1.0);
  EXPECT_THROW(BlockSparseMatrix3::assemble(elements, {}, 3), std::invalid_argument);
}

TEST(ElementMatrices, RejectsAnIncompleteElement) {
  EXPECT_THROW(ElementMatrices(3, {0, 1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(ElementMatrices(0, {}), std::invalid_argument);
  const ElementMatrices m(2, {0, 1, 1, 2});
  EXPECT_EQ(m.num_elements(), 2);
  EXPECT_EQ(m.matrix_size(), 6);
  EXPECT_EQ(m.matrix(1) - m.matrix(0), 36);
}

TEST(BlockSparseMatrix3, EmptyTripletsGiveEmptyColumns) {
  const BlockSparseMatrix3 m = BlockSparseMatrix3::from_triplets({}, 4);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(m.column_begin(c), m.column_end(c));
}

TEST(BlockSparseMatrix3, RejectsATripletOutsideTheMatrix) {
  EXPECT_THROW(BlockSparseMatrix3::from_triplets({Triplet(0, 6, 1.0)}, 2), std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix3::from_triplets({Triplet(-1, 0, 1.0)}, 2), std::invalid_argument);
}

}  // namespace tightfit::block_sparse_matrix_test
