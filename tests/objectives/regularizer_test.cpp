#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "support/finite_difference.hpp"
#include "support/test_pieces.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/regularizer_corner_angle.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/regularizer_smoothness.hpp"
#include "tightfit/objectives/resolution.hpp"

namespace tightfit::regularizer_test {

/// A regular nx × ny grid over [x0, x0+w] × [0, h] (test::grid_piece unjittered, moved
/// by x0), boundary counter-clockwise from the lower left corner, the four corners marked.
PatternPiece grid_piece(const std::string& name, int nx, int ny, double w, double h,
                        double x0 = 0.0) {
  PatternPiece piece = test::grid_piece(nx, ny, w, h, 0.0, 1);
  piece.name = name;
  piece.rest.col(0).array() += x0;
  return piece;
}

std::vector<int> column(int nx, int ny, int i) {
  std::vector<int> c;
  for (int j = 0; j < ny; ++j) c.push_back(j * nx + i);
  return c;
}

/// Two grids sewn along A's right side and B's left side (both listed bottom to top).
/// B is `hb` tall where A is 0.2, so the seam sides differ in length.
Garment two_pieces(double hb = 0.2) {
  Pattern pattern;
  pattern.pieces.push_back(grid_piece("A", 5, 4, 0.3, 0.2));
  pattern.pieces.push_back(grid_piece("B", 4, 4, 0.2, hb, 0.5));
  Seam seam;
  seam.name = "AB";
  seam.a = {0, column(5, 4, 4)};
  seam.b = {1, column(4, 4, 0)};
  pattern.seams.push_back(seam);
  return weld_pattern(pattern);
}

/// A regular n-gon piece (fan around a centre vertex), circumradius `radius`, no corners.
Garment polygon_piece(int n, double radius) {
  Pattern pattern;
  PatternPiece piece;
  piece.name = "polygon";
  piece.rest.resize(n + 1, 2);
  piece.rest.row(n) << 0.0, 0.0;
  piece.triangles.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    piece.rest.row(i) << radius * std::cos(a), radius * std::sin(a);
    piece.triangles.row(i) << n, i, (i + 1) % n;
    piece.boundary.push_back(i);
  }
  pattern.pieces.push_back(piece);
  return weld_pattern(pattern);
}

/// Rest positions with every vertex moved by up to `amount` (m), reproducibly.
Points2 perturbed(const Points2& rest, double amount, unsigned seed) {
  const VecX d = test::random_vector(rest.size(), seed);
  Points2 out = rest;
  out += amount * Eigen::Map<const Points2>(d.data(), rest.rows(), 2);
  return out;
}

/// FD check of ∂T/∂Xbar (and that ∂T/∂x stays zero) at `rest`.
void expect_rest_gradient(const DesignTerm& term, const Points2& rest, double h = 1e-6) {
  const VecX x = VecX::Zero(3);  // regularizers ignore x
  VecX d_x = VecX::Zero(3);
  VecX d_rest = VecX::Zero(rest.size());
  term.add_gradient(DesignState{x, rest}, d_x, d_rest);
  EXPECT_EQ(d_x.norm(), 0.0);
  ASSERT_GT(d_rest.norm(), 0.0) << term.name();
  auto f = [&](const VecX& r) {
    const Points2 p = Eigen::Map<const Points2>(r.data(), rest.rows(), 2);
    return term.value(DesignState{x, p});
  };
  const VecX r0 = Eigen::Map<const VecX>(rest.data(), rest.size());
  const test::FdCheck c = test::check_gradient(f, d_rest, r0, h);
  EXPECT_LT(c.relative_error, 1e-6) << term.name() << " |g| = " << c.analytic_norm;
}

TEST(SeamLengthRegularizer, ValueByHand) {
  const Garment g = two_pieces(0.26);
  // Weights refer to a reference boundary edge of 0.1 m: w = 0.1 / the pair's mean edge.
  const EdgeLengthDifferenceTerm term = seam_length_regularizer(g, {1.0, 0.1});
  ASSERT_EQ(term.pairs().size(), 3u);
  const VecX x;
  const Points2 rest = g.rest_positions();
  // Three edges per side: each differs by (0.26 − 0.2)/3.
  const double w = 0.1 / (0.5 * (0.26 / 3.0 + 0.2 / 3.0));
  for (const auto& pair : term.pairs()) EXPECT_NEAR(pair.weight, w, 1e-12);
  EXPECT_NEAR(term.value({x, rest}), w * 3.0 * std::pow(0.06 / 3.0, 2), 1e-15);
  EXPECT_FALSE(term.depends_on_positions());
  const Garment equal = two_pieces(0.2);
  EXPECT_EQ(seam_length_regularizer(equal).value({x, equal.rest_positions()}), 0.0);
}

TEST(SeamLengthRegularizer, GradientMatchesFiniteDifferences) {
  const Garment g = two_pieces(0.26);
  expect_rest_gradient(seam_length_regularizer(g), perturbed(g.rest_positions(), 0.01, 1));
}

TEST(EvenSpacingRegularizer, ValueByHandOnGrids) {
  const Garment g = two_pieces(0.2);
  const EdgeLengthDifferenceTerm term = even_spacing_regularizer(g, {1.0, 0.1});
  // A: 14 loop vertices; B: 12. Only corners join edges of different length.
  ASSERT_EQ(term.pairs().size(), 14u + 12u);
  const double w = 0.1 / (0.5 * (0.3 / 4 + 0.2 / 3));  // reference edge / mean edge
  const double a = 4.0 * w * std::pow(0.3 / 4 - 0.2 / 3, 2);
  const double b = 0.0;  // B: 0.2/3 both ways
  const VecX x;
  EXPECT_NEAR(term.value({x, g.rest_positions()}), a + b, 1e-15);
}

TEST(EvenSpacingRegularizer, GradientMatchesFiniteDifferences) {
  const Garment g = two_pieces(0.26);
  expect_rest_gradient(even_spacing_regularizer(g), perturbed(g.rest_positions(), 0.01, 2));
}

TEST(BoundarySmoothnessRegularizer, RegularPolygonByHand) {
  const int n = 12;
  const double radius = 0.1;
  const Garment g = polygon_piece(n, radius);
  const BoundarySmoothnessRegularizer term(g);
  ASSERT_EQ(term.triples().size(), static_cast<std::size_t>(n));
  const double edge = 2.0 * radius * std::sin(std::numbers::pi / n);
  const double kappa = 2.0 * std::tan(std::numbers::pi / n);  // turning angle 2π/n
  const VecX x;
  EXPECT_NEAR(term.value({x, g.rest_positions()}), n * kappa * kappa / (2.0 * edge), 1e-12);
}

TEST(BoundarySmoothnessRegularizer, CornersAreExemptAndStraightSidesCostNothing) {
  const Garment g = two_pieces(0.2);
  const BoundarySmoothnessRegularizer term(g);
  EXPECT_EQ(term.triples().size(), 14u - 4u + 12u - 4u);
  const VecX x;
  EXPECT_NEAR(term.value({x, g.rest_positions()}), 0.0, 1e-20);
}

TEST(BoundarySmoothnessRegularizer, GradientMatchesFiniteDifferences) {
  const Garment g = two_pieces(0.26);
  const BoundarySmoothnessRegularizer term(g);
  expect_rest_gradient(term, perturbed(g.rest_positions(), 0.01, 3));
  const Garment p = polygon_piece(9, 0.1);
  expect_rest_gradient(BoundarySmoothnessRegularizer(p), perturbed(p.rest_positions(), 0.01, 4));
}

TEST(CornerAngleRegularizer, ZeroAtTheReferenceAndTheSquaredAngleChangeByHand) {
  const Garment g = two_pieces(0.2);
  const CornerAngleRegularizer term(g);
  ASSERT_EQ(term.triples().size(), 8u);  // four corners per grid
  for (const double theta : term.reference_angles())
    EXPECT_NEAR(theta, std::numbers::pi / 2.0, 1e-12);  // a left turn of 90° at each corner
  const VecX x;
  Points2 rest = g.rest_positions();
  EXPECT_EQ(term.value({x, rest}), 0.0);
  // Piece A's lower-left corner (vertex 0) pulled left along the bottom side by 0.1 m:
  // its neighbour on the left side (0, 0.2/3) now meets it at 90° + atan(0.1 / (0.2/3)).
  rest(0, 0) -= 0.1;
  const double change_at_corner = std::atan2(0.1, 0.2 / 3.0);
  // The turn at the next corner is unchanged (vertex 1 is not a corner: edges 0→1 and
  // 1→2 stay collinear), so only corner 0 contributes.
  EXPECT_NEAR(term.value({x, rest}), change_at_corner * change_at_corner, 1e-12);
}

TEST(CornerAngleRegularizer, GradientMatchesFiniteDifferences) {
  const Garment g = two_pieces(0.26);
  const CornerAngleRegularizer term(g);
  expect_rest_gradient(term, perturbed(g.rest_positions(), 0.01, 11));
  expect_rest_gradient(term, perturbed(g.rest_positions(), 0.03, 12));
}

TEST(CornerAngleRegularizer, ACollapsedCornerEdgeIsInfinite) {
  const Garment g = two_pieces(0.2);
  const CornerAngleRegularizer term(g);
  Points2 rest = g.rest_positions();
  rest.row(1) = rest.row(0);  // the edge from corner 0 to vertex 1 has zero length
  const VecX x;
  EXPECT_TRUE(std::isinf(term.value({x, rest})));
  VecX dx = VecX::Zero(3), dr = VecX::Zero(rest.size());
  EXPECT_THROW(term.add_gradient({x, rest}, dx, dr), SolverError);
}

TEST(BoundarySmoothnessRegularizer, FoldBackIsInfinite) {
  const Garment g = polygon_piece(6, 0.1);
  Points2 rest = g.rest_positions();
  // Vertex 2 beyond vertex 3 on the line from 1: edges 1→2 and 2→3 are antiparallel.
  rest.row(2) = rest.row(1) + 2.0 * (rest.row(3) - rest.row(1));
  const BoundarySmoothnessRegularizer term(g);
  const VecX x;
  EXPECT_TRUE(std::isinf(term.value({x, rest})));
  VecX dx = VecX::Zero(3), dr = VecX::Zero(rest.size());
  EXPECT_THROW(term.add_gradient({x, rest}, dx, dr), SolverError);
}

/// Brute-force ρ of pair (i, j) of loop `loop` along the arc that was shorter at `initial`.
double brute_ratio(const std::vector<int>& loop, const Points2& initial, const Points2& rest, int i,
                   int j) {
  const int n = static_cast<int>(loop.size());
  auto arc = [&](const Points2& p, int from, int to) {  // forward from → to
    double s = 0.0;
    for (int k = from; k != to; k = (k + 1) % n)
      s += (p.row(loop[(k + 1) % n]) - p.row(loop[k])).norm();
    return s;
  };
  const bool forward = arc(initial, i, j) <= arc(initial, j, i);
  const double len = forward ? arc(rest, i, j) : arc(rest, j, i);
  return (rest.row(loop[i]) - rest.row(loop[j])).norm() / len;
}

TEST(CompactnessRegularizer, RatiosAndValueMatchBruteForceWithTheInitialPathKept) {
  Pattern pattern;
  pattern.pieces.push_back(grid_piece("strip", 11, 3, 1.0, 0.12));
  // Break the symmetry so that no pair has two boundary arcs of equal length.
  pattern.pieces[0].rest = perturbed(pattern.pieces[0].rest, 0.003, 8);
  const Garment g = weld_pattern(pattern);
  const double h = 0.05;  // reference boundary edge (m)
  const CompactnessRegularizer term(g, {0.3, 1}, {1.0, h});
  const Points2 initial = g.rest_positions();
  // Bend the strip so that arcs change length unevenly.
  Points2 rest = perturbed(initial, 0.02, 5);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) rest(v, 1) += 0.3 * std::pow(rest(v, 0) - 0.5, 2);
  ASSERT_EQ(term.loops().size(), 1u);
  const auto& loop = term.loops()[0];
  const std::vector<double> rho = term.ratios(rest);
  ASSERT_EQ(rho.size(), loop.pairs.size());
  const int n = static_cast<int>(loop.vertices.size());
  ASSERT_EQ(n, 24);
  // All pairs except the n neighbours (one-edge paths).
  EXPECT_EQ(loop.pairs.size(), static_cast<std::size_t>(n * (n - 1) / 2 - n));
  // A pair weighs σ_i σ_j / h², σ half the two initial boundary edges at each end.
  auto share = [&](int i) {
    auto at = [&](int k) { return initial.row(loop.vertices[(k + n) % n]); };
    return 0.5 * ((at(i + 1) - at(i)).norm() + (at(i) - at(i - 1)).norm()) / h;
  };
  double expected = 0.0;
  for (std::size_t k = 0; k < rho.size(); ++k) {
    const auto& pair = loop.pairs[k];
    const double b = brute_ratio(loop.vertices, initial, rest, pair.i, pair.j);
    EXPECT_NEAR(rho[k], b, 1e-14);
    EXPECT_NEAR(pair.weight, share(pair.i) * share(pair.j), 1e-12);
    if (b < 0.3) expected += pair.weight * std::pow(b - 0.3, 4);
  }
  const VecX x;
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(term.value({x, rest}), expected, 1e-14);
}

TEST(CompactnessRegularizer, GradientMatchesFiniteDifferences) {
  Pattern pattern;
  pattern.pieces.push_back(grid_piece("strip", 11, 3, 1.0, 0.12));
  pattern.pieces.push_back(grid_piece("square", 4, 4, 0.2, 0.2, 2.0));
  const Garment g = weld_pattern(pattern);
  Points2 rest = perturbed(g.rest_positions(), 0.01, 6);
  expect_rest_gradient(CompactnessRegularizer(g, {0.3, 1}), rest);
  expect_rest_gradient(CompactnessRegularizer(g, {0.5, 2}), rest);
}

TEST(CompactnessRegularizer, StrideSubsamplesPairs) {
  Pattern pattern;
  pattern.pieces.push_back(grid_piece("strip", 11, 3, 1.0, 0.12));
  const Garment g = weld_pattern(pattern);
  const CompactnessRegularizer all(g, {0.3, 1});
  const CompactnessRegularizer some(g, {0.3, 3});
  EXPECT_LT(some.loops()[0].pairs.size() * 6, all.loops()[0].pairs.size());
  for (const auto& p : some.loops()[0].pairs) {
    EXPECT_EQ(p.i % 3, 0);
    EXPECT_EQ(p.j % 3, 0);
  }
  EXPECT_THROW(CompactnessRegularizer(g, {0.0, 1}), std::invalid_argument);
  EXPECT_THROW(CompactnessRegularizer(g, {0.3, 0}), std::invalid_argument);
}

TEST(DesignTermSum, WeightsValuesAndGradients) {
  const Garment g = two_pieces(0.26);
  auto seam = std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(g));
  auto smooth = std::make_shared<BoundarySmoothnessRegularizer>(g);
  DesignTermSum sum;
  sum.add(seam, 2.0);
  sum.add(smooth, 0.5);
  sum.add(std::make_shared<CompactnessRegularizer>(g), 0.0);
  EXPECT_THROW(sum.add(seam, -1.0), std::invalid_argument);
  EXPECT_THROW(sum.add(nullptr, 1.0), std::invalid_argument);
  EXPECT_FALSE(sum.depends_on_positions());
  const Points2 rest = perturbed(g.rest_positions(), 0.01, 7);
  const VecX x;
  const DesignState s{x, rest};
  EXPECT_NEAR(sum.value(s), 2.0 * seam->value(s) + 0.5 * smooth->value(s), 1e-15);
  const std::vector<double> parts = sum.weighted_values(s);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[2], 0.0);
  expect_rest_gradient(sum, rest);
}

TEST(Resolution, VertexAreasBoundaryEdgesAndPinnedSharesByHand) {
  // Piece A (0.3 x 0.2 m, 4 x 3 cells) sewn to B (0.2 x 0.2 m, 3 x 3 cells).
  const Garment g = two_pieces(0.2);
  const VecX areas = garment_vertex_areas(g);
  EXPECT_NEAR(areas.sum(), 0.3 * 0.2 + 0.2 * 0.2, 1e-15);  // the pattern's rest area
  const ResolutionReference r = resolution_of(g);
  EXPECT_NEAR(r.vertex_area, areas.sum() / g.num_garment_vertices(), 1e-15);
  // Boundary: A 1.0 m over 14 edges, B 0.8 m over 12.
  EXPECT_NEAR(r.boundary_edge, (1.0 + 0.8) / 26.0, 1e-15);
  EXPECT_TRUE(r.known());
  EXPECT_FALSE(ResolutionReference{}.known());
  const ResolutionReference given{2.0, 3.0};
  EXPECT_EQ(resolution_or_own(given, g).boundary_edge, 3.0);
  EXPECT_EQ(resolution_or_own({}, g).boundary_edge, r.boundary_edge);
  // No pinned boundary: no pinned shares.
  EXPECT_EQ(pinned_vertex_lengths(g).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace tightfit::regularizer_test
