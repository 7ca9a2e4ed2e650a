/// `tightfit optimize` says which rule ended a run: result.json ("stop_rule" and
/// "stop_reason"), the last line printed, and history.json marks the iteration whose
/// design the run returns; --time-limit ends a run by its wall-clock budget.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit::optimize_stop_cli_test {

namespace fs = std::filesystem;

class OptimizeStopCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_optimize_stop_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A sleeve 10 % short around on a rigid cylinder, its stretch wanted in [1.02, 1.06].
    nlohmann::json scene = nlohmann::json::parse(R"({
      "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
      "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                             "hoop_scale": 0.9, "axial_scale": 0.95, "edge_length": 0.016,
                             "jitter": 0.3, "pin_first_ring": true, "pin_last_ring": true}},
      "body_material": {"rigid": true},
      "optimize": {"objectives": {"stretch": {"weight": 1, "min": 1.02, "max": 1.06}},
                   "regularizers": {"seam_length": 1}, "max_iterations": 60}
    })");
    std::ofstream(dir_ / "scene.json") << scene.dump(2);
  }
  void TearDown() override { fs::remove_all(dir_); }

  nlohmann::json read_json(const std::string& name) const {
    std::ifstream in(dir_ / "out" / name);
    return nlohmann::json::parse(in);
  }
  test::CliRun optimize(const std::string& args) const {
    return test::run_cli("optimize " + (dir_ / "scene.json").string() + " --out " +
                         (dir_ / "out").string() + " " + args);
  }
  /// The last non-empty line of `text`.
  static std::string last_line(const std::string& text) {
    const size_t end = text.find_last_not_of('\n');
    const size_t begin = text.rfind('\n', end);
    return text.substr(begin == std::string::npos ? 0 : begin + 1, end - begin);
  }

  fs::path dir_;
};

TEST_F(OptimizeStopCli, TheIterationLimitIsNamedEverywhere) {
  const test::CliRun r = optimize("--max-iterations 3 --terse");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json o = read_json("result.json")["optimization"];
  EXPECT_EQ(o["stop_rule"], "iteration_limit");
  EXPECT_EQ(o["stop_reason"].get<std::string>().rfind("not converged: the iteration limit", 0), 0u);
  EXPECT_FALSE(o["converged"].get<bool>());
  EXPECT_EQ(o["iterations"], 3);
  EXPECT_EQ(last_line(r.output).rfind("  stopped (iteration_limit): not converged", 0), 0u)
      << last_line(r.output);
  // Every step decreased T: the best design is the last one, marked in history.json.
  EXPECT_EQ(o["best_iteration"], 3);
  EXPECT_FALSE(o["best_restored"].get<bool>());
  const nlohmann::json history = read_json("history.json");
  EXPECT_EQ(history["best_iteration"], 3);
  int marked = 0;
  for (const auto& it : history["iterations"])
    if (it.value("best", false)) {
      ++marked;
      EXPECT_EQ(it["iteration"], 3);
      EXPECT_EQ(it["objective"], o["objective_final"]);
    }
  EXPECT_EQ(marked, 1);
}

TEST_F(OptimizeStopCli, ARunConvergesByTheGradientOrTargetRule) {
  const test::CliRun r = optimize("--terse");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json o = read_json("result.json")["optimization"];
  std::printf("  %s\n", last_line(r.output).c_str());
  EXPECT_TRUE(o["converged"].get<bool>()) << o["stop_reason"];
  const std::string rule = o["stop_rule"];
  EXPECT_TRUE(rule == "gradient" || rule == "target_value" || rule == "stationary") << rule;
  EXPECT_EQ(last_line(r.output).rfind("  stopped (" + rule + "): converged", 0), 0u)
      << last_line(r.output);
}

TEST_F(OptimizeStopCli, TheTimeLimitEndsTheRunWithItsOutputs) {
  const test::CliRun r = optimize("--time-limit 1e-6 --terse");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json o = read_json("result.json")["optimization"];
  EXPECT_EQ(o["stop_rule"], "time_limit");
  EXPECT_EQ(o["iterations"], 0);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "pattern.svg"));
  EXPECT_EQ(last_line(r.output).rfind("  stopped (time_limit): not converged: the time limit", 0),
            0u)
      << last_line(r.output);
}

}  // namespace tightfit::optimize_stop_cli_test
