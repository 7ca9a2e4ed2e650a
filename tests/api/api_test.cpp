/// The public API (api/tightfit.hpp): a scene from a file or a JSON document, simulate,
/// optimize with a callback that stops the run, resume, and the outputs — the same as
/// the command line's.
#include <gtest/gtest.h>

#include <fstream>

#include "report/support/fit_test_tools.hpp"
#include "support/cli_run.hpp"
#include "tightfit/api/tightfit.hpp"

namespace tightfit::api_test {

namespace fs = std::filesystem;
using test::source_path;

const char* const kSleeve = "examples/sleeve_rigid_cylinder.json";
const char* const kOptimizeSleeve = "examples/optimize_sleeve_stretch.json";

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

TEST(ApiScene, ReadValidatesWithoutLoading) {
  api::Scene scene = api::Scene::read(source_path(kSleeve));
  EXPECT_FALSE(scene.loaded());
  EXPECT_EQ(scene.file(), source_path(kSleeve).string());
  EXPECT_FALSE(scene.has_optimization());
  try {
    scene.optimization();
    FAIL() << "a scene without an \"optimize\" section has no optimization";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), scene.file());
    EXPECT_NE(std::string(e.what()).find("/optimize: missing"), std::string::npos) << e.what();
  }
}

TEST(ApiScene, JsonDocumentErrorsNameTheGivenNameAndPath) {
  nlohmann::json document = read_json(source_path(kSleeve));
  document["fabric"] = {{"youngs_modulus", "stiff"}};
  try {
    api::Scene::from_json(document, "front-end scene");
    FAIL() << "a string Young's modulus is bad input";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "front-end scene");
    EXPECT_NE(std::string(e.what()).find("/fabric/youngs_modulus"), std::string::npos) << e.what();
  }
}

TEST(ApiSimulate, JsonDocumentAndFileReachTheSameEquilibrium) {
  api::Scene from_file = api::Scene::read(source_path(kSleeve));
  api::Scene from_json =
      api::Scene::from_json(read_json(source_path(kSleeve)), "sleeve", source_path("examples"));
  const api::SimulationRun a = api::simulate(from_file);
  const api::SimulationRun b = api::simulate(from_json);
  ASSERT_TRUE(a.newton.converged);
  EXPECT_EQ(a.newton.iterations, b.newton.iterations);
  EXPECT_EQ(a.newton.final_force_norm, b.newton.final_force_norm);
  EXPECT_TRUE(from_file.simulation().garment_positions() ==
              from_json.simulation().garment_positions());
}

TEST(ApiSimulate, NewtonProgressIsReportedDuringTheCallOnly) {
  api::Scene scene = api::Scene::read(source_path(kSleeve));
  int steps = 0;
  api::SimulateOptions options;
  options.on_newton_step = [&](const NewtonIteration& step, double seconds) {
    ++steps;
    EXPECT_GT(step.force_norm, 0.0);
    EXPECT_GE(seconds, 0.0);
  };
  const api::SimulationRun run = api::simulate(scene, options);
  ASSERT_TRUE(run.newton.converged);
  // One call per accepted step of the coupled solve (and of the garment-first solve).
  int accepted = 0;
  for (const NewtonIteration& it : run.newton.history) accepted += it.step_size > 0.0;
  EXPECT_GE(steps, accepted);
  EXPECT_GT(steps, 0);
  // The callback was the call's: a later solve does not report to it.
  const int before = steps;
  scene.simulation().solve();
  EXPECT_EQ(steps, before);
}

TEST(ApiSimulate, OutputsAreTheCommandLines) {
  // `tightfit simulate` runs on the API: its result.json and the API's agree on
  // everything but the run's date and timings.
  test::TempDir dir("api_simulate");
  const test::CliRun cli = test::run_cli("simulate " + source_path(kSleeve).string() + " --out " +
                                         (dir / "cli").string());
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  api::Scene scene = api::Scene::read(source_path(kSleeve));
  const api::SimulationRun run = api::simulate(scene);
  fs::create_directories(dir / "api");
  const api::WrittenOutputs written = api::write_simulation_outputs(scene, run, dir / "api");
  for (const char* file : {"garment.ply", "body.ply", "result.json", "state.json", "report.html"})
    EXPECT_NE(std::find(written.files.begin(), written.files.end(), file), written.files.end())
        << file;
  for (const std::string& file : written.files) EXPECT_TRUE(fs::exists(dir / "api" / file)) << file;
  const nlohmann::json from_cli = read_json(dir / "cli" / "result.json");
  const nlohmann::json from_api = read_json(dir / "api" / "result.json");
  EXPECT_EQ(from_api, written.result);
  for (const char* key : {"fit", "counts", "energies_j", "measurements", "fabric"})
    EXPECT_EQ(from_cli[key], from_api[key]) << key;
  EXPECT_EQ(from_cli["newton"]["iterations"], from_api["newton"]["iterations"]);
  EXPECT_EQ(from_cli["newton"]["final_force_residual_n"],
            from_api["newton"]["final_force_residual_n"]);
  EXPECT_EQ(test::read_text(dir / "cli" / "garment.ply"),
            test::read_text(dir / "api" / "garment.ply"));
}

TEST(ApiOptimize, TheCallbackStopsTheRunAndResumeContinuesIt) {
  test::TempDir dir("api_optimize");
  api::Scene scene = api::Scene::read(source_path(kOptimizeSleeve));
  ASSERT_TRUE(scene.has_optimization());
  api::Optimization optimization(scene);
  EXPECT_GT(optimization.num_parameters(), 0);
  EXPECT_EQ(optimization.term_names().size(), optimization.objective().entries().size());
  std::vector<int> seen;
  const OptimizationResult result = optimization.run([&](const OptimizationIteration& it) {
    seen.push_back(it.iteration);
    return it.iteration < 2;
  });
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(result.interrupted);
  EXPECT_EQ(result.iterations, 2);
  ASSERT_EQ(optimization.history().size(), 3u);
  EXPECT_LT(optimization.history().back().value, optimization.history().front().value);
  ASSERT_TRUE(optimization.initial_garment().has_value());
  const api::WrittenOutputs written =
      api::write_optimization_outputs(optimization, result, dir.path());
  EXPECT_EQ(written.result["optimization"]["iterations"], 2);
  EXPECT_EQ(written.result["optimization"]["objective_final"], optimization.history().back().value);
  ASSERT_TRUE(fs::exists(dir / "checkpoint.json"));
  EXPECT_EQ(read_json(dir / "history.json")["iterations"].size(), 3u);

  // A new optimization of the same scene continues from the checkpoint.
  api::Scene again = api::Scene::read(source_path(kOptimizeSleeve));
  api::OptimizeOptions options;
  options.max_iterations = 3;
  api::Optimization resumed(again, options);
  resumed.resume(dir / "checkpoint.json");
  EXPECT_TRUE(resumed.resumed());
  const OptimizationResult more = resumed.run();
  EXPECT_EQ(more.iterations, 3);
  EXPECT_FALSE(more.interrupted);
  ASSERT_EQ(resumed.history().size(), 4u);
  EXPECT_EQ(resumed.history()[2].value, optimization.history()[2].value);
  EXPECT_FALSE(resumed.initial_garment().has_value());
}

TEST(ApiOptimize, AResumeFileOfAnotherSceneIsNamed) {
  test::TempDir dir("api_resume");
  std::ofstream(dir / "checkpoint.json") << "{\"format\": \"something else\"}";
  api::Scene scene = api::Scene::read(source_path(kOptimizeSleeve));
  api::Optimization optimization(scene);
  try {
    optimization.resume(dir / "checkpoint.json");
    FAIL() << "not a checkpoint";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), (dir / "checkpoint.json").string());
  }
}

TEST(ApiOptimize, TheResultSaysTheRuleAndTheBestDesignAndTheHistoryMarksIt) {
  api::Scene scene = api::Scene::read(source_path(kOptimizeSleeve));
  api::OptimizeOptions options;
  options.max_iterations = 2;
  api::Optimization optimization(scene, options);
  const OptimizationResult result = optimization.run();
  const nlohmann::json o = api::optimization_result_json(optimization, result);
  EXPECT_EQ(o["stop_rule"], stop_rule_name(result.rule));
  EXPECT_EQ(o["stop_reason"], result.stop_reason);
  EXPECT_EQ(o["best_iteration"], result.best_iteration);
  EXPECT_EQ(o["objective_final"], result.final_value);
  EXPECT_EQ(optimization.best_iteration_so_far(), result.best_iteration);
  const nlohmann::json history = optimization.history_json(result.best_iteration);
  EXPECT_EQ(history["best_iteration"], result.best_iteration);
  EXPECT_EQ(history["iterations"].size(), optimization.history().size());
}

TEST(ApiOptimize, ATimeLimitEndsTheRunByItsRule) {
  api::Scene scene = api::Scene::read(source_path(kOptimizeSleeve));
  api::OptimizeOptions options;
  options.time_limit = 1e-9;  // over before the first iteration ends
  api::Optimization optimization(scene, options);
  const OptimizationResult result = optimization.run();
  EXPECT_EQ(result.rule, StopRule::kTimeLimit) << result.stop_reason;
  EXPECT_LE(result.iterations, 1);
}

TEST(ApiOptimize, ACheckpointOfAnotherSceneDocumentIsRefusedNamingWhatChanged) {
  test::TempDir dir("api_resume_inputs");
  nlohmann::json document = read_json(source_path(kOptimizeSleeve));
  api::Scene scene = api::Scene::from_json(document, "sleeve.json", source_path("examples"));
  api::OptimizeOptions options;
  options.max_iterations = 1;
  api::Optimization optimization(scene, options);
  optimization.run();
  optimization.write_checkpoint(dir / "checkpoint.json");
  // The same document resumes; only the limits differ (a resumed run may change them).
  document["optimize"]["max_iterations"] = 3;
  api::Scene same = api::Scene::from_json(document, "sleeve.json", source_path("examples"));
  api::Optimization resumed(same);
  resumed.resume(dir / "checkpoint.json");
  EXPECT_TRUE(resumed.resumed());
  // Another stretch target is another scene.
  document["optimize"]["objectives"]["stretch"]["max"] = 1.07;
  api::Scene other = api::Scene::from_json(document, "sleeve.json", source_path("examples"));
  api::Optimization refused(other);
  try {
    refused.resume(dir / "checkpoint.json");
    FAIL() << "a checkpoint of another scene was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), (dir / "checkpoint.json").string());
    EXPECT_NE(std::string(e.what()).find("sleeve.json changed"), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::api_test
