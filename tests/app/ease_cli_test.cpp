// The ease table of real runs: `tightfit simulate` on the left leg of the MakeHuman legs
// body with its rig measures at the skeleton's standard levels, `tightfit export` gives the
// same table, and a bad "measurements" entry stops the run before any output.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "report/support/fit_test_tools.hpp"
#include "support/cli_run.hpp"

namespace tightfit {
namespace ease_cli_test {

nlohmann::json read_json(const std::filesystem::path& file) {
  return nlohmann::json::parse(test::read_text(file));
}

}  // namespace ease_cli_test

using namespace ease_cli_test;

TEST(EaseCli, TheLeftLegIsMeasuredAtTheSkeletonsStandardLevels) {
  const test::TempDir dir("ease_leg");
  const std::string scene =
      std::string(TIGHTFIT_SOURCE_DIR) + "/examples/left_leg_anchored_regular.json";
  const test::CliRun run = test::run_cli("simulate " + scene + " --out " + (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json levels = read_json(dir / "run" / "result.json").at("measurements");
  std::set<std::string> measured, skipped;
  for (const nlohmann::json& level : levels) {
    EXPECT_EQ(level.at("origin"), "skeleton");
    const std::string name = level.at("name").get<std::string>();
    if (level.at("status") == "skipped") {
      skipped.insert(name);
      EXPECT_NE(level.at("reason").get<std::string>().find("all the way around"), std::string::npos)
          << name;
      continue;
    }
    measured.insert(name);
    // Pieces cut 0.85 across the grain (around the leg): an ease of about -15 %, give or
    // take the flattening's local distortion.
    const double ease = level.at("ease_percent").get<double>();
    EXPECT_GT(ease, -22.0) << name;
    EXPECT_LT(ease, -10.0) << name;
    double pieces = 0.0;
    for (const nlohmann::json& piece : level.at("pieces"))
      pieces += piece.at("pattern_width_m").get<double>();
    EXPECT_NEAR(pieces, level.at("pattern_circumference_m").get<double>(), 1e-12) << name;
  }
  // The left leg from the thigh to the calf; the ankle lies below the cuff, the right leg
  // and the arms carry no garment: left out. The hip plane crosses the garment's top edge.
  for (const char* name : {"thigh.L", "mid-thigh.L", "knee.L", "calf.L"})
    EXPECT_TRUE(measured.count(name)) << name;
  for (const auto& name : measured) EXPECT_TRUE(name.ends_with(".L")) << name;
  EXPECT_EQ(skipped, (std::set<std::string>{"hip"}));
  // Each piece's label carries its lines of the table (calf.L ... ease -NN %).
  const std::string svg = test::read_text(dir / "run" / "pattern.svg");
  const std::string dxf = test::read_text(dir / "run" / "pattern.dxf");
  for (const std::string& text : {svg, dxf}) {
    EXPECT_NE(text.find("calf.L "), std::string::npos);
    EXPECT_NE(text.find(", ease -"), std::string::npos);
  }

  // The export regenerates the same table.
  const test::CliRun exported =
      test::run_cli("export " + (dir / "run").string() + " --out " + (dir / "copy").string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_EQ(read_json(dir / "copy" / "result.json").at("measurements"), levels);
}

TEST(EaseCli, ALevelOnABoneWithoutASkeletonStopsTheRunBeforeAnyOutput) {
  const test::TempDir dir("ease_bad");
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04, "edge_length": 0.016}},
    "body_material": {"rigid": true},
    "measurements": [{"name": "calf", "point": {"bone": "lowerleg01.L", "at": 0.45}, "normal": "along_bone"}]
  })";
  const test::CliRun run = test::run_cli("simulate " + (dir / "scene.json").string() + " --out " +
                                         (dir / "run").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(
      run.output.find("scene.json: /measurements/0: anchored on the skeleton, but there is none"),
      std::string::npos)
      << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "run"));
}

}  // namespace tightfit
