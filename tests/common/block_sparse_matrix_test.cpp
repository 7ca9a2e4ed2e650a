#include "tightfit/common/block_sparse_matrix.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

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

TEST(BlockSparseMatrix3, EmptyTripletsGiveEmptyColumns) {
  const BlockSparseMatrix3 m = BlockSparseMatrix3::from_triplets({}, 4);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(m.column_begin(c), m.column_end(c));
}

TEST(BlockSparseMatrix3, RejectsATripletOutsideTheMatrix) {
  EXPECT_THROW(BlockSparseMatrix3::from_triplets({Triplet(0, 6, 1.0)}, 2), std::invalid_argument);
  EXPECT_THROW(BlockSparseMatrix3::from_triplets({Triplet(-1, 0, 1.0)}, 2), std::invalid_argument);
}

}  // namespace tightfit::block_sparse_matrix_test
