/// A pattern optimization whose piece degrades and is remeshed, checkpointed right after
/// the remeshing: the checkpoint file holds the remeshed pattern and the carried L-BFGS
/// memory, a run resumed from it continues like the uninterrupted one, and a checkpoint
/// of another pattern is refused naming the JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "design/adjoint_test_scene.hpp"
#include "design/remesh_test_terms.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/design/pattern_remesh.hpp"
#include "tightfit/garment/piece_mesher.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"

namespace tightfit::remesh_checkpoint_test {

using test::DipTerm;
using test::expect_monotone_across_remeshes;
using test::make_sleeve_scene;
using test::SleeveSceneOptions;

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

}  // namespace tightfit::remesh_checkpoint_test
