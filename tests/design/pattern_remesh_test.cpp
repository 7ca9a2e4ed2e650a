/// Remeshing of degraded pieces during pattern optimization: the embedding transfer,
/// the remeshed garment (seams weld, corners and pinned rings kept), and an optimizer
/// run whose piece degrades, is remeshed and goes on decreasing the objective.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "adjoint_test_scene.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/optimization_checkpoint.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/design/pattern_remesh.hpp"
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit::pattern_remesh_test {

using test::make_sleeve_scene;
using test::SleeveSceneOptions;

/// Pulls the vertices of the pinned boundary `ring` of the pattern towards the curve
/// y = top − depth sin²(π x / width): the top edge of the sleeve piece dips in its
/// middle, squashing the triangles below it. T = ½ Σ (y_v − g(x_v))² (m²), Xbar only.
class DipTerm : public DesignTerm {
 public:
  DipTerm(const Garment& g, const std::string& ring, double top, double depth, double width)
      : top_(top), depth_(depth), width_(width) {
    for (const PinnedBoundary& pin : g.pattern.pinned)
      if (pin.name == ring)
        for (int v : pin.vertices) vertices_.push_back(g.topology->piece_offset[pin.piece] + v);
    if (vertices_.empty()) throw std::invalid_argument("DipTerm: no such ring");
  }
  std::string name() const override { return "dip"; }
  double value(const DesignState& s) const override {
    double t = 0.0;
    for (int v : vertices_) t += 0.5 * std::pow(residual(s, v), 2);
    return t;
  }
  void add_gradient(const DesignState& s, VecX&, VecX& d_rest) const override {
    const double k = std::numbers::pi / width_;
    for (int v : vertices_) {
      const double r = residual(s, v);
      const double slope = -depth_ * k * std::sin(2.0 * k * s.rest(v, 0));  // g'(x)
      d_rest[2 * v] += -r * slope;
      d_rest[2 * v + 1] += r;
    }
  }
  bool depends_on_positions() const override { return false; }

 private:
  double residual(const DesignState& s, int v) const {
    const double sn = std::sin(std::numbers::pi * s.rest(v, 0) / width_);
    return s.rest(v, 1) - (top_ - depth_ * sn * sn);
  }
  std::vector<int> vertices_;
  double top_, depth_, width_;
};

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

/// Accepted values decrease; across a remeshing the next value is compared with the
/// remeshed pattern's value.
void expect_monotone_across_remeshes(const std::vector<OptimizationIteration>& h) {
  for (size_t k = 1; k < h.size(); ++k) {
    const double before = h[k - 1].remesh && h[k - 1].remesh->failure.empty()
                              ? h[k - 1].remesh->value
                              : h[k - 1].value;
    EXPECT_LT(h[k].value, before) << "iteration " << h[k].iteration;
  }
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

TEST(PatternOptimizerRemesh, ADegradingPieceIsRemeshedAndTheRunGoesOn) {
  SleeveSceneOptions so;
  so.jitter = 0.0;  // a regular mesh: 44° smallest angle
  auto scene = make_sleeve_scene(so);
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  const PatternPiece& piece0 = sim.garment().pattern.pieces[0];
  const double width = piece0.rest.col(0).maxCoeff(), top = piece0.rest.col(1).maxCoeff();
  const double depth = 0.45 * top;
  auto factory = [&](const GarmentSimulation& s) {
    auto sum = std::make_shared<DesignTermSum>();
    sum->add(std::make_shared<DipTerm>(s.garment(), "last ring", top, depth, width), 1.0);
    return sum;
  };
  DesignProblemOptions po;
  po.remesh.min_angle_deg = 30.0;
  DesignProblem problem(sim, factory(sim), po, factory);
  PatternOptimizerOptions oo;
  oo.max_iterations = 40;
  oo.value_tolerance = 1e-10;
  PatternOptimizer optimizer(problem, oo);
  const std::string dir = ::testing::TempDir() + "tightfit_remesh_checkpoint";
  std::filesystem::create_directories(dir);
  const std::vector<std::string> names = term_names(problem.objective());
  bool checkpoint_written = false;
  const OptimizationResult result = optimizer.run([&](const OptimizationIteration& it) {
    std::printf("  it %2d  T %.4e  |g| %.2e  trials %d  newton %d", it.iteration, it.value,
                it.gradient_norm, it.line_search_trials, it.newton_iterations);
    if (it.remesh)
      std::printf("  REMESH %s: min angle %.1f -> %.1f deg, T -> %.4e, %d params, newton %d%s",
                  it.remesh->pieces.at(0).c_str(), it.remesh->min_angle_before,
                  it.remesh->min_angle_after, it.remesh->value, it.remesh->parameters,
                  it.remesh->newton_iterations, it.remesh->failure.c_str());
    std::printf("\n");
    if (it.remesh && !checkpoint_written) {
      write_checkpoint(dir + "/checkpoint.json", optimizer.checkpoint(), names);
      checkpoint_written = true;
    }
  });
  std::printf("  %s; T %.4e -> %.4e\n", result.stop_reason.c_str(), result.initial_value,
              result.final_value);
  const auto& history = optimizer.history();
  int remeshes = 0;
  for (const OptimizationIteration& it : history)
    if (it.remesh) {
      ++remeshes;
      EXPECT_TRUE(it.remesh->failure.empty()) << it.remesh->failure;
      EXPECT_LT(it.remesh->min_angle_before, 30.0);
      EXPECT_GT(it.remesh->min_angle_after, 30.0);
      EXPECT_EQ(it.remesh->pieces, std::vector<std::string>{"sleeve"});
    }
  EXPECT_GE(remeshes, 1);
  expect_monotone_across_remeshes(history);
  // Iterations after the first remeshing decreased the objective further.
  size_t first = 0;
  while (first < history.size() && !history[first].remesh) ++first;
  ASSERT_LT(first + 1, history.size());
  EXPECT_LT(history.back().value, history[first].remesh->value);
  EXPECT_LT(result.final_value, 1e-3 * result.initial_value);
  // The final state: a converged equilibrium on a pattern whose seam still welds.
  EmbeddedEquilibrium& eq = sim.problem();
  EXPECT_LE(eq.force_norm(eq.gradient()),
            sim.newton().options().relative_force_tolerance * sim.force_scale());
  const Seam& seam = sim.garment().pattern.seams[0];
  ASSERT_EQ(seam.a.vertices.size(), seam.b.vertices.size());
  for (size_t k = 0; k < seam.a.vertices.size(); ++k)
    EXPECT_EQ(sim.garment().topology->pattern_to_garment[seam.a.vertices[k]],
              sim.garment().topology->pattern_to_garment[seam.b.vertices[k]]);
  EXPECT_GE(piece_quality(sim.garment().pattern.pieces[0]).min_angle_deg, 0.75 * 30.0);

  // The remesh record survives the history's JSON form.
  const OptimizationIteration& rec = history[first];
  const OptimizationIteration back = iteration_from_json(iteration_json(rec, names), names, "test");
  ASSERT_TRUE(back.remesh.has_value());
  EXPECT_EQ(back.remesh->value, rec.remesh->value);
  EXPECT_EQ(back.remesh->parameters, rec.remesh->parameters);

  // The checkpoint written right after the remeshing holds the remeshed pattern; a run
  // resumed from it on a problem built from the scene continues like the uninterrupted
  // one: same parameter count, same iterations, same final pattern and equilibrium.
  ASSERT_TRUE(checkpoint_written);
  const OptimizationCheckpoint saved = read_checkpoint(dir + "/checkpoint.json", names);
  ASSERT_TRUE(saved.remeshed.has_value());
  EXPECT_EQ(saved.iteration, history[first].iteration);
  EXPECT_EQ(saved.parameters.size(), history[first].remesh->parameters);
  // The L-BFGS pairs are carried onto the remeshed parameters (memory_transfer.hpp).
  ASSERT_FALSE(saved.memory.s.empty());
  for (size_t k = 0; k < saved.memory.s.size(); ++k) {
    EXPECT_EQ(saved.memory.s[k].size(), history[first].remesh->parameters);
    EXPECT_GT(saved.memory.s[k].dot(saved.memory.y[k]), 0.0);
  }
  auto fresh = make_sleeve_scene(so);
  fresh->sim->solve();
  DesignProblem fresh_problem(*fresh->sim, factory(*fresh->sim), po, factory);
  PatternOptimizer resumed(fresh_problem, oo);
  resumed.resume(saved);
  EXPECT_EQ(fresh_problem.num_parameters(), history[first].remesh->parameters);
  const OptimizationResult again = resumed.run();
  EXPECT_EQ(again.iterations, result.iterations);
  EXPECT_EQ(again.stop_reason, result.stop_reason);
  const auto& h2 = resumed.history();
  ASSERT_EQ(h2.size(), history.size());
  for (size_t k = first + 1; k < history.size(); ++k)
    EXPECT_NEAR(h2[k].value, history[k].value, 1e-9 * history[first].remesh->value + 1e-14)
        << "iteration " << k;
  const Garment& g1 = sim.garment();
  const Garment& g2 = fresh->sim->garment();
  std::printf(
      "  resumed after the remeshing: final T %.6e vs %.6e; max rest difference %.1e m, "
      "max position difference %.1e m\n",
      again.final_value, result.final_value,
      (g2.rest_positions() - g1.rest_positions()).cwiseAbs().maxCoeff(),
      (fresh->sim->garment_positions() - sim.garment_positions()).cwiseAbs().maxCoeff());
  ASSERT_EQ(g2.num_garment_vertices(), g1.num_garment_vertices());
  ASSERT_EQ(g2.topology->pattern_triangles, g1.topology->pattern_triangles);
  EXPECT_LE((g2.rest_positions() - g1.rest_positions()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((fresh->sim->garment_positions() - sim.garment_positions()).cwiseAbs().maxCoeff(),
            1e-7);

  // A checkpoint whose remeshed pattern does not fit the scene is refused, naming the
  // JSON path of the mismatch.
  OptimizationCheckpoint bad = saved;
  bad.remeshed->pattern.pieces[0].name = "other";
  auto other = make_sleeve_scene(so);
  DesignProblem other_problem(*other->sim, factory(*other->sim), po, factory);
  PatternOptimizer refused(other_problem, oo);
  try {
    refused.resume(bad);
    ADD_FAILURE() << "a checkpoint of another pattern was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/remeshed/pattern/pieces/0/name"), std::string::npos)
        << e.what();
  }
  nlohmann::json j = checkpoint_json(saved, names);
  j["remeshed"]["pattern"]["seams"][0]["b"]["vertices"].erase(0);
  try {
    checkpoint_from_json(j, names, "ck.json");
    ADD_FAILURE() << "unequal seam sides were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ck.json: /remeshed/pattern/seams/0"), std::string::npos)
        << e.what();
  }
}

}  // namespace tightfit::pattern_remesh_test
