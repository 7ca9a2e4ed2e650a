#include "tightfit/design/biharmonic_coordinates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/test_pieces.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit::biharmonic_coordinates_test {

/// An nx × ny grid over [0,w]×[0,h] with interior vertices jittered by 20 % of the
/// spacing and random diagonals; boundary loop counter-clockwise from the origin.
PatternPiece jittered_grid(int nx, int ny, double w, double h, unsigned seed) {
  return test::grid_piece(nx, ny, w, h, 0.2, seed);
}

/// A CGAL-meshed non-convex piece (an L shape with a curved bump), boundary first.
PatternPiece meshed_piece() {
  std::vector<Vec2> outline;
  auto line = [&](Vec2 a, Vec2 b, int n) {
    for (int k = 0; k < n; ++k) outline.push_back(a + (b - a) * k / double(n));
  };
  line({0.0, 0.0}, {0.3, 0.0}, 12);
  line({0.3, 0.0}, {0.3, 0.1}, 4);
  for (int k = 0; k < 8; ++k) {  // half-ellipse from (0.3, 0.1) over (0.2, 0.15) to (0.1, 0.1)
    const double a = std::numbers::pi * k / 8.0;
    outline.push_back({0.2 + 0.1 * std::cos(a), 0.1 + 0.05 * std::sin(a)});
  }
  line({0.1, 0.1}, {0.1, 0.3}, 8);
  line({0.1, 0.3}, {0.0, 0.3}, 4);
  line({0.0, 0.3}, {0.0, 0.0}, 12);
  Points2 b(outline.size(), 2);
  for (std::size_t i = 0; i < outline.size(); ++i) b.row(i) = outline[i].transpose();
  const PieceMesh mesh = mesh_piece(b, 0.02, 5);
  PatternPiece piece;
  piece.name = "L";
  piece.rest = mesh.vertices;
  piece.triangles = mesh.triangles;
  for (int i = 0; i < static_cast<int>(outline.size()); ++i) piece.boundary.push_back(i);
  return piece;
}

Points2 affine(const Points2& p, const Mat2& a, const Vec2& t) {
  Points2 q(p.rows(), 2);
  for (Eigen::Index i = 0; i < p.rows(); ++i) q.row(i) = (a * p.row(i).transpose() + t).transpose();
  return q;
}

Points2 boundary_rows(const PatternPiece& piece, const Points2& all) {
  Points2 b(piece.boundary.size(), 2);
  for (std::size_t j = 0; j < piece.boundary.size(); ++j) b.row(j) = all.row(piece.boundary[j]);
  return b;
}

void expect_affine_precision(const PatternPiece& piece) {
  const PieceBiharmonicCoordinates w(piece);
  Mat2 a;
  a << 1.3, -0.4, 0.25, 0.8;
  const Vec2 t(0.7, -1.1);
  const Points2 target = affine(piece.rest, a, t);
  const Points2 result = w.apply(boundary_rows(piece, target));
  const double size = (piece.rest.colwise().maxCoeff() - piece.rest.colwise().minCoeff()).norm();
  EXPECT_LT((result - target).cwiseAbs().maxCoeff(), 1e-10 * size) << piece.name;
}

TEST(BiharmonicCoordinates, ReproducesAffineMapsOnJitteredGrid) {
  expect_affine_precision(jittered_grid(12, 9, 0.4, 0.25, 3));
}

TEST(BiharmonicCoordinates, ReproducesAffineMapsOnMeshedNonConvexPiece) {
  const PatternPiece piece = meshed_piece();
  ASSERT_GT(piece.rest.rows(), 100);
  expect_affine_precision(piece);
}

TEST(BiharmonicCoordinates, InterpolatesBoundaryAndIsAPartitionOfUnity) {
  const PatternPiece piece = meshed_piece();
  const PieceBiharmonicCoordinates w(piece);
  ASSERT_EQ(w.num_vertices(), piece.rest.rows());
  ASSERT_EQ(w.num_boundary(), static_cast<int>(piece.boundary.size()));
  for (int j = 0; j < w.num_boundary(); ++j) {
    VecX unit = VecX::Zero(w.num_boundary());
    unit[j] = 1.0;
    EXPECT_EQ((w.weights().row(piece.boundary[j]).transpose() - unit).cwiseAbs().maxCoeff(), 0.0);
  }
  EXPECT_LT((w.weights().rowwise().sum() - VecX::Ones(w.num_vertices())).cwiseAbs().maxCoeff(),
            1e-12);
  // Biharmonic (not harmonic) weights: some are negative, none is wild.
  EXPECT_LT(w.weights().minCoeff(), 0.0);
  EXPECT_GT(w.weights().minCoeff(), -0.5);
}

TEST(BiharmonicCoordinates, BendingTheBoundaryKeepsTheInteriorValid) {
  // Bend the grid's boundary into an annular sector: every interior triangle keeps its
  // orientation (no fold-over) and its area changes smoothly.
  const PatternPiece piece = jittered_grid(16, 8, 0.5, 0.2, 5);
  const PieceBiharmonicCoordinates w(piece);
  auto bend = [](const Vec2& p) {
    const double r = 0.4 + p.y(), a = p.x() / 0.5;  // 1 rad of arc
    return Vec2(r * std::sin(a), r * std::cos(a) - 0.4);
  };
  Points2 b = boundary_rows(piece, piece.rest);
  for (Eigen::Index j = 0; j < b.rows(); ++j) b.row(j) = bend(b.row(j).transpose()).transpose();
  const Points2 x = w.apply(b);
  double ratio_min = 1e9, ratio_max = 0.0;
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    auto area = [&](const Points2& p) {
      const Vec2 e1 = (p.row(piece.triangles(t, 1)) - p.row(piece.triangles(t, 0))).transpose();
      const Vec2 e2 = (p.row(piece.triangles(t, 2)) - p.row(piece.triangles(t, 0))).transpose();
      return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    };
    // The bend keeps the orientation and scales areas by about (0.4 + y)/0.5.
    const double r = area(x) / area(piece.rest);
    ratio_min = std::min(ratio_min, r);
    ratio_max = std::max(ratio_max, r);
  }
  EXPECT_GT(ratio_min, 0.6);
  EXPECT_LT(ratio_max, 1.5);
}

TEST(BiharmonicCoordinates, PatternLayoutMatchesItsMatrix) {
  Pattern pattern;
  pattern.pieces.push_back(jittered_grid(6, 5, 0.2, 0.15, 1));
  pattern.pieces.push_back(jittered_grid(7, 4, 0.3, 0.1, 2));
  const BiharmonicCoordinates coords(pattern);
  const int np = static_cast<int>(pattern.pieces[0].rest.rows() + pattern.pieces[1].rest.rows());
  ASSERT_EQ(coords.num_pattern_vertices(), np);
  ASSERT_EQ(coords.num_parameter_points(), static_cast<int>(pattern.pieces[0].boundary.size() +
                                                            pattern.pieces[1].boundary.size()));
  EXPECT_EQ(coords.parameter_vertices()[pattern.pieces[0].boundary.size()],
            pattern.pieces[0].rest.rows() + pattern.pieces[1].boundary[0]);

  const SparseMatrix w = coords.matrix();
  ASSERT_EQ(w.rows(), 2 * np);
  ASSERT_EQ(w.cols(), coords.num_parameters());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecX p(coords.num_parameters());
  for (auto& v : p) v = u(rng);
  const Points2 rest = coords.rest_positions(p);
  const VecX flat = Eigen::Map<const VecX>(rest.data(), rest.size());
  EXPECT_LT((flat - w * p).cwiseAbs().maxCoeff(), 1e-14);
  // Boundary vertices take their parameters; parameters() reads them back.
  EXPECT_LT((coords.parameters(rest) - p).cwiseAbs().maxCoeff(), 1e-15);

  VecX g(2 * np);
  for (auto& v : g) v = u(rng);
  EXPECT_LT((coords.pull_back(g) - w.transpose() * g).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(BiharmonicCoordinates, RejectsBadBoundaryLoops) {
  PatternPiece piece = jittered_grid(4, 4, 1.0, 1.0, 1);
  piece.boundary.push_back(piece.boundary.front());
  EXPECT_THROW(PieceBiharmonicCoordinates{piece}, InputError);
  piece.boundary = {0, 1};
  EXPECT_THROW(PieceBiharmonicCoordinates{piece}, InputError);
  piece.boundary = {0, 1, 99};
  EXPECT_THROW(PieceBiharmonicCoordinates{piece}, InputError);
}

TEST(BiharmonicCoordinates, RejectsInvertedTriangles) {
  PatternPiece piece = jittered_grid(4, 4, 1.0, 1.0, 1);
  piece.rest.row(5) = Vec2(2.5, 2.5).transpose() / 3.0;  // interior vertex (1,1) pushed past (2,2)
  EXPECT_THROW(PieceBiharmonicCoordinates{piece}, InputError);
}

}  // namespace tightfit::biharmonic_coordinates_test
