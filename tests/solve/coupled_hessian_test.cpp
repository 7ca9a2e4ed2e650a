#include "tightfit/solve/coupled_hessian.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "tightfit/common/parallel.hpp"

namespace tightfit::coupled_hessian_test {

/// Symmetric random triplets over `n` vertices: full 3×3 blocks on vertex pairs
/// (i, i+1), (i, i+s) and the diagonal, written twice where pairs repeat.
std::vector<Triplet> symmetric_blocks(int n, int stride, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Triplet> t;
  auto add = [&](int a, int b) {
    const Mat3 B = Mat3::NullaryExpr([&](Eigen::Index, Eigen::Index) { return value(rng); });
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        if (a == b) {
          t.emplace_back(3 * a + r, 3 * a + c, B(r, c) + B(c, r));
        } else {
          t.emplace_back(3 * a + r, 3 * b + c, B(r, c));
          t.emplace_back(3 * b + c, 3 * a + r, B(r, c));
        }
      }
  };
  for (int i = 0; i < n; ++i) {
    add(i, i);
    add(i, (i + 1) % n);
    add(i, (i + stride) % n);
  }
  return t;
}

struct Case {
  CoupledHessianFactors factors;
  std::vector<Triplet> garment, body;
};

/// ng garment vertices (every fifth pinned) with stencils of 3–7 of nb body vertices
/// (every seventh pinned).
Case random_case(int ng, int nb, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Case c;
  CoupledHessianFactors& f = c.factors;
  int next = 0;
  f.garment_dof.assign(ng, -1);
  for (int i = 0; i < ng; ++i)
    if (i % 5 != 2) {
      f.garment_dof[i] = next;
      next += 2;
    }
  f.body_dof.assign(nb, -1);
  for (int a = 0; a < nb; ++a)
    if (a % 7 != 3) {
      f.body_dof[a] = next;
      next += 3;
    }
  f.num_dofs = next;
  std::vector<int> all(nb);
  std::iota(all.begin(), all.end(), 0);
  f.stencil_start.push_back(0);
  f.garment_forces.resize(ng, 3);
  for (int i = 0; i < ng; ++i) {
    std::shuffle(all.begin(), all.end(), rng);
    const int size = 3 + i % 5;
    for (int j = 0; j < size; ++j) {
      f.stencil_vertex.push_back(all[j]);
      f.weight.push_back(value(rng));
      f.weight_u.push_back(value(rng));
      f.weight_v.push_back(value(rng));
    }
    f.stencil_start.push_back(static_cast<int>(f.stencil_vertex.size()));
    f.tangents.push_back(
        Mat32::NullaryExpr([&](Eigen::Index, Eigen::Index) { return value(rng); }));
    const double off = value(rng);
    f.curvature_terms.push_back((Mat2() << value(rng), off, off, value(rng)).finished());
    f.garment_forces.row(i) = Vec3(value(rng), value(rng), value(rng)).transpose();
  }
  c.garment = symmetric_blocks(ng, 4, rng);
  c.body = symmetric_blocks(nb, 3, rng);
  f.garment = BlockSparseMatrix3::from_triplets(c.garment, ng);
  f.body = BlockSparseMatrix3::from_triplets(c.body, nb);
  return c;
}

/// Jᵀ H_xx J + E by Eigen's sparse products, from the same data.
SparseMatrix reference(const Case& c) {
  const CoupledHessianFactors& f = c.factors;
  const int ng = static_cast<int>(f.garment_dof.size());
  std::vector<Triplet> j, e;
  for (int i = 0; i < ng; ++i) {
    const int d = f.garment_dof[i];
    const Vec3 g = f.garment_forces.row(i).transpose();
    if (d >= 0)
      for (int r = 0; r < 3; ++r) {
        j.emplace_back(3 * i + r, d, f.tangents[i](r, 0));
        j.emplace_back(3 * i + r, d + 1, f.tangents[i](r, 1));
      }
    if (d >= 0)
      for (int r = 0; r < 2; ++r)
        for (int s = 0; s < 2; ++s) e.emplace_back(d + r, d + s, f.curvature_terms[i](r, s));
    for (int k = f.stencil_start[i]; k < f.stencil_start[i + 1]; ++k) {
      const int b = f.body_dof[f.stencil_vertex[k]];
      if (b < 0) continue;
      for (int r = 0; r < 3; ++r) {
        j.emplace_back(3 * i + r, b + r, f.weight[k]);
        if (d < 0) continue;
        e.emplace_back(d, b + r, f.weight_u[k] * g[r]);
        e.emplace_back(b + r, d, f.weight_u[k] * g[r]);
        e.emplace_back(d + 1, b + r, f.weight_v[k] * g[r]);
        e.emplace_back(b + r, d + 1, f.weight_v[k] * g[r]);
      }
    }
  }
  for (const Triplet& t : c.body) {
    const int r = f.body_dof[t.row() / 3], s = f.body_dof[t.col() / 3];
    if (r >= 0 && s >= 0) e.emplace_back(r + t.row() % 3, s + t.col() % 3, t.value());
  }
  SparseMatrix J(3 * ng, f.num_dofs), Hxx(3 * ng, 3 * ng), E(f.num_dofs, f.num_dofs);
  J.setFromTriplets(j.begin(), j.end());
  Hxx.setFromTriplets(c.garment.begin(), c.garment.end());
  E.setFromTriplets(e.begin(), e.end());
  return SparseMatrix(SparseMatrix(J.transpose() * Hxx * J) + E);
}

TEST(CoupledHessian, MatrixIsTheTripleProductPlusTheExtraTerms) {
  const Case c = random_case(40, 30, 1);
  const CoupledHessian h(c.factors);
  const SparseMatrix H = h.matrix();
  const SparseMatrix R = reference(c);
  ASSERT_EQ(H.rows(), c.factors.num_dofs);
  EXPECT_LT((MatX(H) - MatX(R)).norm(), 1e-12 * MatX(R).norm());
  // The same structural pattern as the sparse product's (zeros stored).
  EXPECT_EQ(H.nonZeros(), R.nonZeros());
  EXPECT_TRUE(H.isCompressed());
}

TEST(CoupledHessian, MultiplyIsTheProductWithTheMatrix) {
  const Case c = random_case(35, 25, 2);
  const CoupledHessian h(c.factors);
  const VecX v = VecX::LinSpaced(c.factors.num_dofs, -1.0, 2.0);
  const VecX Hv = reference(c) * v;
  EXPECT_LT((h.multiply(v) - Hv).norm(), 1e-12 * Hv.norm());
}

TEST(CoupledHessian, SameMatrixAndProductForEveryThreadCount) {
  const int saved = thread_count();
  const Case c = random_case(600, 400, 3);  // enough vertices for the loops to split
  const CoupledHessian h(c.factors);
  const VecX v = VecX::LinSpaced(c.factors.num_dofs, -1.0, 2.0);
  set_thread_count(1);
  const SparseMatrix one = h.matrix();
  const VecX one_product = h.multiply(v);
  for (int threads : {2, 3}) {
    set_thread_count(threads);
    EXPECT_EQ((h.multiply(v) - one_product).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
    const SparseMatrix other = h.matrix();
    ASSERT_EQ(other.nonZeros(), one.nonZeros());
    EXPECT_TRUE(std::equal(one.valuePtr(), one.valuePtr() + one.nonZeros(), other.valuePtr()));
    EXPECT_TRUE(std::equal(one.innerIndexPtr(), one.innerIndexPtr() + one.nonZeros(),
                           other.innerIndexPtr()));
  }
  set_thread_count(saved);
}

TEST(CoupledHessian, RejectsBodyDofsBeforeGarmentDofs) {
  Case c = random_case(10, 8, 4);
  std::swap(c.factors.garment_dof[0], c.factors.body_dof[0]);
  EXPECT_THROW(CoupledHessian{c.factors}, std::invalid_argument);
}

}  // namespace tightfit::coupled_hessian_test
