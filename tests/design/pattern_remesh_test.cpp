/// Remeshing of degraded pieces during pattern optimization: the embedding transfer,
/// the remeshed garment (seams weld, corners and pinned rings kept), and an optimizer
/// run whose piece degrades, is remeshed and goes on decreasing the objective
/// (tests/scene/remesh_checkpoint_test.cpp: the same run checkpointed and resumed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "adjoint_test_scene.hpp"
#include "remesh_test_terms.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/design/pattern_remesh.hpp"
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit::pattern_remesh_test {

using test::DipTerm;
using test::make_sleeve_scene;
using test::SleeveSceneOptions;

/// The 3D position of a surface point on the scene's current body.
Vec3 position(const GarmentSimulation& sim, const SurfacePoint& s) {
  return sim.surface().position(s,
                                sim.body_positions().topRows(sim.surface().num_control_vertices()));
}

TEST(PieceQuality, AnglesAtSharpCornersOfTheOutlineDoNotCountOthersDo) {
  // A 20° spike split in two at its apex: the apex angles (10°) are bounded by the
  // outline, not by the mesh; the other angles are 80° and 90°.
  PatternPiece spike;
  const double t = std::tan(10.0 * std::numbers::pi / 180.0);
  spike.rest.resize(4, 2);
  spike.rest << 0, 0, 1, -t, 1, 0, 1, t;
  spike.triangles.resize(2, 3);
  spike.triangles << 0, 1, 2, 0, 2, 3;
  spike.boundary = {0, 1, 2, 3};
  EXPECT_NEAR(piece_quality(spike).min_angle_deg, 80.0, 1e-9);

  // A square whose centre vertex sits near its bottom edge: thin triangles at the
  // square's 90° corners count.
  PatternPiece square;
  square.rest.resize(5, 2);
  square.rest << 0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0.02;
  square.triangles.resize(4, 3);
  square.triangles << 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
  square.boundary = {0, 1, 2, 3};
  EXPECT_NEAR(piece_quality(square).min_angle_deg, std::atan2(0.02, 0.5) * 180.0 / std::numbers::pi,
              1e-9);
}

TEST(EmbeddingTransfer, IsExactAtOldVerticesAndOnTheSurfaceElsewhere) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  const Garment& g = sim.garment();
  const EmbeddingTransfer transfer(g, sim.problem().state(), sim.garment_positions(),
                                   sim.surface());
  const PatternPiece& piece = g.pattern.pieces[0];
  double worst = 0.0, worst_edge = 0.0;
  for (Eigen::Index v = 0; v < piece.rest.rows(); ++v) {
    const Vec3 old = sim.garment_positions().row(g.topology->pattern_to_garment[v]).transpose();
    worst = std::max(
        worst,
        (position(sim, transfer.at_rest_point(0, piece.rest.row(v).transpose())) - old).norm());
    worst_edge = std::max(
        worst_edge, (position(sim, transfer.on_edge(0, static_cast<int>(v), 0, 0.0)) - old).norm());
  }
  std::printf("  old vertices: max distance %.2e m (rest point), %.2e m (edge start)\n", worst,
              worst_edge);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_edge, 1e-9);
  // A triangle centroid: the projection of the interpolated point, which lies within the
  // chord's sag (edge² / 8R ≈ 0.6 mm here) of it.
  const Vec2 c = (piece.rest.row(piece.triangles(0, 0)) + piece.rest.row(piece.triangles(0, 1)) +
                  piece.rest.row(piece.triangles(0, 2)))
                     .transpose() /
                 3.0;
  Vec3 interpolated = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    interpolated += sim.garment_positions()
                        .row(g.topology->pattern_to_garment[piece.triangles(0, k)])
                        .transpose() /
                    3.0;
  const Vec3 x = position(sim, transfer.at_rest_point(0, c));
  EXPECT_LT((x - interpolated).norm(), 1e-3);
  EXPECT_NEAR(std::hypot(x.x(), x.y()), 0.05, 2e-3);  // on the capsule's side
}

TEST(RemeshGarment, ResampledSeamsWeldAndTheTransferredStateConverges) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  const Garment old = sim.garment();
  const double h = 0.7 * mean_edge_length(old.pattern.pieces[0]);  // finer than before
  const PatternRemeshResult r = remesh_garment(old, sim.problem().state(), sim.garment_positions(),
                                               sim.surface(), {0}, {h}, 10);
  const Garment& g = r.garment;
  ASSERT_EQ(r.remeshed, std::vector<int>{0});
  const PatternPiece& piece = g.pattern.pieces[0];
  std::printf(
      "  %d -> %d pattern vertices, %d -> %d garment vertices, min angle %.1f -> %.1f deg\n",
      old.num_pattern_vertices(), g.num_pattern_vertices(), old.num_garment_vertices(),
      g.num_garment_vertices(),
      min_angle_deg(old.pattern.pieces[0].rest, old.pattern.pieces[0].triangles),
      min_angle_deg(piece.rest, piece.triangles));
  EXPECT_GT(g.num_pattern_vertices(), old.num_pattern_vertices());
  // The seam: equal counts on both sides, welded pairwise, more vertices than before.
  const Seam& seam = g.pattern.seams[0];
  ASSERT_EQ(seam.a.vertices.size(), seam.b.vertices.size());
  EXPECT_GT(seam.a.vertices.size(), old.pattern.seams[0].a.vertices.size());
  for (size_t k = 0; k < seam.a.vertices.size(); ++k)
    EXPECT_EQ(g.topology->pattern_to_garment[seam.a.vertices[k]],
              g.topology->pattern_to_garment[seam.b.vertices[k]]);
  // Welding merged exactly the seam pairs (the corners meet the pinned rings).
  EXPECT_EQ(g.num_garment_vertices(),
            g.num_pattern_vertices() - static_cast<int>(seam.a.vertices.size()));
  // Corners and the pinned rings' ends are old vertices, at their old surface points.
  ASSERT_EQ(piece.corners.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const Vec2 q = piece.rest.row(piece.corners[k]);
    EXPECT_EQ(q, Vec2(old.pattern.pieces[0].rest.row(old.pattern.pieces[0].corners[k])));
    const SurfacePoint a = g.embedding[g.topology->pattern_to_garment[piece.corners[k]]];
    const SurfacePoint b =
        old.embedding[old.topology->pattern_to_garment[old.pattern.pieces[0].corners[k]]];
    EXPECT_EQ(a.face, b.face);
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.v, b.v);
  }
  ASSERT_EQ(g.pattern.pinned.size(), 2u);
  for (const PinnedBoundary& pin : g.pattern.pinned) {
    EXPECT_GT(pin.vertices.size(), 3u);
    for (int v : pin.vertices) EXPECT_NEAR(piece.rest(v, 1), piece.rest(pin.vertices[0], 1), 1e-12);
  }
  // The new garment converges from the transferred state, and its rings stayed put.
  sim.replace_garment(r.garment, r.state);
  const NewtonReport report = sim.solve();
  std::printf("  transferred equilibrium: %d Newton iterations, residual %.2e N\n",
              report.iterations, report.final_force_norm);
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.iterations, 8);
}

TEST(DesignProblemRemesh, AFailureAfterTheNewGarmentIsBuiltPutsEverythingBack) {
  // The objective factory builds other terms for the remeshed garment (a logic error,
  // std::invalid_argument): remesh() reports it and leaves the problem as it was.
  SleeveSceneOptions so;
  so.jitter = 0.0;
  auto scene = make_sleeve_scene(so);
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  const PatternPiece& piece0 = sim.garment().pattern.pieces[0];
  const double width = piece0.rest.col(0).maxCoeff(), top = piece0.rest.col(1).maxCoeff();
  int calls = 0;
  auto factory = [&](const GarmentSimulation& s) {
    auto sum = std::make_shared<DesignTermSum>();
    sum->add(std::make_shared<DipTerm>(s.garment(), "last ring", top, 0.2 * top, width), 1.0);
    if (++calls > 1)
      sum->add(std::make_shared<DipTerm>(s.garment(), "last ring", top, 0.1 * top, width), 1.0);
    return sum;
  };
  DesignProblem problem(sim, factory(sim), {}, factory);
  const VecX p = problem.initial_parameters();
  const DesignEvaluation before = problem.evaluate(p, true);
  ASSERT_TRUE(before.ok) << before.failure;
  problem.accept();
  const int parameters = problem.num_parameters();
  const int vertices = sim.garment().num_garment_vertices();

  const RemeshOutcome out = problem.remesh({0});
  EXPECT_FALSE(out.ok);
  EXPECT_NE(out.failure.find("objective factory"), std::string::npos) << out.failure;
  EXPECT_EQ(problem.num_parameters(), parameters);
  EXPECT_EQ(sim.garment().num_garment_vertices(), vertices);
  EXPECT_EQ(problem.objective().entries().size(), 1u);
  const DesignEvaluation after = problem.evaluate(p, true);
  ASSERT_TRUE(after.ok) << after.failure;
  EXPECT_NEAR(after.value, before.value, 1e-12 * std::abs(before.value));
}

}  // namespace tightfit::pattern_remesh_test
