/// "Never a NaN accepted": a run whose state turns non-finite ends with a SolverError
/// naming the stage, and no file it wrote (history, checkpoints) holds a NaN, an
/// infinity or a null standing for a number.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>

#include "design/adjoint_test_scene.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/design/finite_state.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"

namespace tightfit::non_finite_run_test {

namespace fs = std::filesystem;

constexpr double kNanValue = std::numeric_limits<double>::quiet_NaN();

std::shared_ptr<DesignTermSum> nan_run_objective(GarmentSimulation& sim) {
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(
      std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
  for (const auto& r : test::regularizers(sim.garment())) objective->add(r, 1e-4);
  return objective;
}

std::string read_whole_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Every file of `dir` as text: a NaN, an infinity or a null (nlohmann's NaN) anywhere.
std::string non_finite_tokens(const fs::path& dir) {
  static const std::regex token(R"(\b(nan|inf|infinity|null)\b)", std::regex::icase);
  std::string found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string text = read_whole_file(e.path());
    std::smatch m;
    if (std::regex_search(text, m, token))
      found += e.path().filename().string() + ": '" + m.str() + "' ";
  }
  return found;
}

TEST(NonFiniteRun, FindsTheFirstNonFiniteNumberOfAStateOrPattern) {
  EmbeddedState state;
  state.garment = {{0, 0.25, 0.5}, {1, 0.5, kNanValue}};
  state.body = Points3::Zero(3, 3);
  EXPECT_EQ(non_finite_place(state), "garment surface point 1 (u, v)");
  state.garment[1].v = 0.5;
  EXPECT_EQ(non_finite_place(state), "");
  state.body(2, 0) = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(non_finite_place(state), "body vertex 2");
  Pattern pattern;
  pattern.pieces.resize(2);
  pattern.pieces[1].name = "back";
  pattern.pieces[0].rest = Points2::Zero(3, 2);
  pattern.pieces[1].rest = Points2::Zero(4, 2);
  EXPECT_EQ(non_finite_place(pattern), "");
  pattern.pieces[1].rest(3, 1) = kNanValue;
  EXPECT_EQ(non_finite_place(pattern), "piece 'back', vertex 3");
}

TEST(NonFiniteRun, ANonFiniteStateEndsTheRunAndNoOutputHoldsANaN) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_non_finite_run_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path checkpoint_file = dir / "checkpoint.json";

  // A good run of two iterations writes its history and checkpoints as the CLI does.
  auto scene = test::make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  auto objective = nan_run_objective(sim);
  const std::vector<std::string> names = term_names(*objective);
  DesignProblem problem(sim, objective);
  PatternOptimizerOptions options;
  options.max_iterations = 2;
  PatternOptimizer optimizer(problem, options);
  optimizer.run([&](const OptimizationIteration&) {
    nlohmann::json history = nlohmann::json::array();
    for (const OptimizationIteration& it : optimizer.history())
      history.push_back(iteration_json(it, names));
    write_json_atomically(dir / "history.json", {{"iterations", history}}, 2);
    write_checkpoint(checkpoint_file, optimizer.checkpoint(), names);
  });
  ASSERT_EQ(optimizer.checkpoint().iteration, 2);
  const std::string good = read_whole_file(checkpoint_file);

  // The state turns non-finite (a body vertex at NaN): the checkpoint writer refuses it
  // and keeps the last good one.
  OptimizationCheckpoint bad = optimizer.checkpoint();
  bad.state.body(0, 1) = kNanValue;
  try {
    write_checkpoint(checkpoint_file, bad, names);
    ADD_FAILURE() << "a NaN checkpoint was written";
  } catch (const SolverError& e) {
    EXPECT_NE(
        std::string(e.what()).find(checkpoint_file.string() +
                                   ": not written: non-finite number (nan) at /state/body/0/1"),
        std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_whole_file(checkpoint_file), good);

  // A run started from that state: a solver error naming the stage, nothing accepted.
  auto scene2 = test::make_sleeve_scene();
  DesignProblem problem2(*scene2->sim, nan_run_objective(*scene2->sim));
  PatternOptimizer resumed(problem2, options);
  resumed.resume(bad);
  int reported = 0;
  try {
    resumed.run([&](const OptimizationIteration&) { ++reported; });
    ADD_FAILURE() << "the run started from a NaN state";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("initial equilibrium (resumed at iteration 2): the starting pattern "
                        "cannot be evaluated"),
              std::string::npos)
        << what;
  }
  EXPECT_EQ(reported, 0);

  // Every file of the folder: no NaN, infinity or null.
  EXPECT_EQ(non_finite_tokens(dir), "");
  EXPECT_TRUE(fs::exists(dir / "history.json"));
  fs::remove_all(dir);
}

}  // namespace tightfit::non_finite_run_test
