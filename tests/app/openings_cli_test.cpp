/// Pieces with openings (holes) through the whole pipeline, run with the built CLI:
/// the adjoint gradient against finite differences with the hole's rim among the design
/// parameters and every boundary regularizer on, and an optimization that remeshes the
/// holed piece and writes patterns, report and pieces.json with the opening.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit {
namespace openings_cli_test {

namespace fs = std::filesystem;

/// A two-panel sleeve cut from a rigid cylinder (radius 5 cm along z) between
/// z = ±4 cm, with a round opening of radius 1.2 cm in the front panel and its cuffs
/// pinned; pieces scaled to 90 % around.
nlohmann::json sleeve_with_opening_scene() {
  return nlohmann::json::parse(R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.012},
    "body_material": {"rigid": true},
    "garment": {
      "layout": {
        "region": [{"name": "lower", "point": [0, 0, -0.04], "normal": [0, 0, 1]},
                   {"name": "upper", "point": [0, 0, 0.04], "normal": [0, 0, -1]}],
        "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0]}],
        "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
        "openings": [{"name": "window", "center": [0.05, 0, 0], "radius": 0.012}],
        "pinned": [{"name": "lower cuff", "on_plane": "lower"}, {"name": "upper cuff", "on_plane": "upper"}]
      },
      "pattern": {"edge_length": 0.01, "scale": [0.95, 0.9], "grain": [0, 0, 1]}
    },
    "optimize": {"objectives": {"stretch": {"weight": 1, "min": 1.02, "max": 1.06}},
                 "max_iterations": 1}
  })");
}

class OpeningsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_openings_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write_scene(const nlohmann::json& scene) {
    std::ofstream(dir_ / "scene.json") << scene.dump(2);
    return dir_ / "scene.json";
  }
  fs::path dir_;
};

TEST_F(OpeningsCli, AFailedBuildKeepsTheLayoutsWarnings) {
  // The mask: its mouth and nostril openings cut the closed lips' cavity off each half
  // (a warning). With an area tolerance no flattening meets, the build fails; the
  // warnings come with the error.
  std::ifstream in(std::string(TIGHTFIT_SOURCE_DIR) + "/examples/optimize_mask_pressure.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["body"]["mesh"] = std::string(TIGHTFIT_SOURCE_DIR) + "/data/bodies/mh_head_neutral.obj";
  scene["garment"]["layout"]["area_tolerance"] = 1e-9;
  const auto r =
      test::run_cli("layout " + write_scene(scene).string() + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("area_tolerance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("after the warning: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cuts a part of"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(OpeningsCli, AdjointGradientAgreesWithFiniteDifferencesWithTheRimAsParameters) {
  nlohmann::json s = sleeve_with_opening_scene();
  s["optimize"]["objectives"]["pressure"] = {{"weight", 1e-9}, {"min_mmhg", 3}, {"max_mmhg", 5}};
  s["optimize"]["regularizers"] = {{"seam_length", 1},
                                   {"boundary_spacing", 0.1},
                                   {"boundary_smoothness", 1e-6},
                                   {"compactness", {{"weight", 1}, {"min_ratio", 0.5}}}};
  const test::CliRun r = test::run_cli("check-gradient " + write_scene(s).string() +
                                       " --directions 2 --perturb 0.1 --max-error 1e-5");
  std::printf("%s", r.output.c_str());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* term :
       {"stretch", "pressure", "boundary spacing", "boundary smoothness", "compactness"})
    EXPECT_NE(r.output.find(std::string("  ") + term + " "), std::string::npos) << term;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("largest relative error: ([0-9.e+-]+)")));
  EXPECT_LT(std::stod(m[1]), 1e-5);
}

TEST_F(OpeningsCli, ARemeshedRunKeepsTheOpeningInEveryOutput) {
  // Pushed towards an across-the-grain stretch of 1.6-1.7, the pieces narrow, their
  // triangles flatten and they are remeshed (as in OptimizeCli's remesh scene).
  nlohmann::json s = sleeve_with_opening_scene();
  s["optimize"]["objectives"] = {
      {"directional_stretch",
       {{"weight", 1}, {"min", 1.6}, {"max", 1.7}, {"direction", "across_grain"}}}};
  s["optimize"]["max_iterations"] = 4;
  s["optimize"]["remesh"] = {{"min_angle_deg", 40}};
  const fs::path out = dir_ / "out";
  const test::CliRun r =
      test::run_cli("optimize " + write_scene(s).string() + " --out " + out.string());
  std::printf("%s", r.output.c_str());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream history_file(out / "history.json");
  const nlohmann::json history = nlohmann::json::parse(history_file);
  int remeshes = 0;
  for (const auto& it : history["iterations"])
    if (it.contains("remesh") && !it["remesh"].contains("failure")) ++remeshes;
  EXPECT_GE(remeshes, 1);
  std::ifstream pieces_file(out / "pieces.json");
  const nlohmann::json pieces = nlohmann::json::parse(pieces_file);
  ASSERT_EQ(pieces["pieces"].size(), 2u);
  const auto& front = pieces["pieces"][0];
  EXPECT_EQ(front["name"], "front");
  ASSERT_EQ(front["holes"].size(), 1u);
  EXPECT_GE(front["holes"][0].size(), 6u);
  ASSERT_EQ(front["openings_mm"].size(), 1u);
  EXPECT_EQ(front["openings_mm"][0].size(), front["holes"][0].size());
  EXPECT_TRUE(pieces["pieces"][1]["holes"].empty());
  // The remesher resampled the rim evenly (its points moved as design parameters).
  double shortest = 1e9, longest = 0.0;
  const auto& rim = front["holes"][0];
  for (size_t i = 0; i < rim.size(); ++i) {
    const auto& a = front["rest"][rim[i].get<size_t>()];
    const auto& b = front["rest"][rim[(i + 1) % rim.size()].get<size_t>()];
    const double d = std::hypot(a[0].get<double>() - b[0].get<double>(),
                                a[1].get<double>() - b[1].get<double>());
    shortest = std::min(shortest, d);
    longest = std::max(longest, d);
  }
  EXPECT_LT(longest, 2.0 * shortest);
  std::ifstream svg_file(out / "pattern.svg");
  const std::string svg((std::istreambuf_iterator<char>(svg_file)),
                        std::istreambuf_iterator<char>());
  EXPECT_NE(svg.find("class=\"cut opening\""), std::string::npos);
  // The saved state reads back: export regenerates the outputs from it.
  const test::CliRun e =
      test::run_cli("export " + out.string() + " --out " + (dir_ / "again").string());
  EXPECT_EQ(e.exit_code, 0) << e.output;
  std::ifstream again_file(dir_ / "again" / "pieces.json");
  const nlohmann::json again = nlohmann::json::parse(again_file);
  EXPECT_EQ(again["pieces"][0]["holes"], front["holes"]);
}

}  // namespace openings_cli_test
}  // namespace tightfit
