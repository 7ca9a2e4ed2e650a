/// The L-BFGS pairs carried across a remeshing (design/memory_transfer.hpp): unchanged
/// points keep their values exactly; on a refined outline the pairs are the same smooth
/// fields sampled at the new points (y scaled by the spacing) and keep their curvature
/// sᵀy; points never take values from another piece.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tightfit/design/memory_transfer.hpp"

namespace tightfit::memory_transfer_test {

/// `n` points on a circle of radius r around (cx, 0), all of piece `piece`, as p.
VecX circle(int n, double r, double cx, double phase = 0.0) {
  VecX p(2 * n);
  for (int j = 0; j < n; ++j) {
    const double t = 2.0 * std::numbers::pi * (j + phase) / n;
    p[2 * j] = cx + r * std::cos(t);
    p[2 * j + 1] = r * std::sin(t);
  }
  return p;
}

/// A pair sampled at points p (angle about (cx, 0)): s a smooth displacement field, y a
/// smooth field times the spacing h (a gradient per point).
void sample(const VecX& p, double cx, double h, VecX& s, VecX& y) {
  s.resize(p.size());
  y.resize(p.size());
  for (Eigen::Index j = 0; 2 * j < p.size(); ++j) {
    const double t = std::atan2(p[2 * j + 1], p[2 * j] - cx);
    s.segment<2>(2 * j) = 1e-3 * Eigen::Vector2d(std::cos(t), 0.5 * std::sin(2 * t));
    y.segment<2>(2 * j) = h * Eigen::Vector2d(std::cos(t) + 0.2, std::sin(2 * t));
  }
}

TEST(MemoryTransfer, UnchangedPointsKeepTheirPairsExactly) {
  const VecX p = circle(40, 0.1, 0.0);
  LbfgsMemory m;
  VecX s, y;
  sample(p, 0.0, 0.1 * 2 * std::numbers::pi / 40, s, y);
  m.s.push_back(s);
  m.y.push_back(y);
  const ParameterPoints pts = parameter_points(p, std::vector<int>(40, 0));
  const LbfgsMemory out = transfer_memory(m, pts, pts);
  ASSERT_EQ(out.s.size(), 1u);
  EXPECT_EQ((out.s[0] - s).norm(), 0.0);
  EXPECT_NEAR((out.y[0] - y).norm(), 0.0, 1e-15 * y.norm());
}

TEST(MemoryTransfer, ARefinedOutlineCarriesTheSameFieldsAndCurvature) {
  const double r = 0.1;
  const int n_old = 40, n_new = 70;
  const double h_old = 2 * std::numbers::pi * r / n_old, h_new = 2 * std::numbers::pi * r / n_new;
  const VecX p_old = circle(n_old, r, 0.0), p_new = circle(n_new, r, 0.0, 0.3);
  VecX s_old, y_old, s_want, y_want;
  sample(p_old, 0.0, h_old, s_old, y_old);
  sample(p_new, 0.0, h_new, s_want, y_want);
  LbfgsMemory m;
  m.s.push_back(s_old);
  m.y.push_back(y_old);
  const LbfgsMemory out = transfer_memory(m, parameter_points(p_old, std::vector<int>(n_old, 0)),
                                          parameter_points(p_new, std::vector<int>(n_new, 0)));
  ASSERT_EQ(out.s.size(), 1u);
  // Linear interpolation of fields sampled every 9°: errors of a few percent at most.
  EXPECT_LT((out.s[0] - s_want).norm(), 0.02 * s_want.norm());
  EXPECT_LT((out.y[0] - y_want).norm(), 0.02 * y_want.norm());
  const double before = s_old.dot(y_old), after = out.s[0].dot(out.y[0]);
  EXPECT_NEAR(after / before, 1.0, 0.03) << before << " vs " << after;
}

TEST(MemoryTransfer, PointsTakeValuesFromTheirOwnPieceOnly) {
  // Two pieces side by side; piece 1's points sit right next to piece 0's outline.
  const VecX a = circle(20, 0.05, 0.0), b = circle(20, 0.05, 0.1001);
  VecX p(a.size() + b.size());
  p << a, b;
  std::vector<int> pieces(40, 0);
  std::fill(pieces.begin() + 20, pieces.end(), 1);
  LbfgsMemory m;
  VecX s = VecX::Zero(p.size()), y = VecX::Zero(p.size());
  s.head(a.size()).setConstant(1.0);  // piece 0 moves, piece 1 does not
  y.head(a.size()).setConstant(1.0);
  m.s.push_back(s);
  m.y.push_back(y);
  const ParameterPoints pts = parameter_points(p, pieces);
  const LbfgsMemory out = transfer_memory(m, pts, pts);
  ASSERT_EQ(out.s.size(), 1u);
  EXPECT_EQ(out.s[0].tail(b.size()).norm(), 0.0);
  EXPECT_EQ(out.s[0].head(a.size()), s.head(a.size()));
}

TEST(MemoryTransfer, PairsThatLoseTheirCurvatureAreDropped) {
  const VecX p = circle(10, 0.1, 0.0);
  LbfgsMemory m;
  m.s.push_back(VecX::Ones(p.size()));
  m.y.push_back(-VecX::Ones(p.size()));  // sᵀy < 0: never a valid pair
  const ParameterPoints pts = parameter_points(p, std::vector<int>(10, 0));
  EXPECT_TRUE(transfer_memory(m, pts, pts).s.empty());
}

}  // namespace tightfit::memory_transfer_test
