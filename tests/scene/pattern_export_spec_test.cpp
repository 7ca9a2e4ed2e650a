#include "tightfit/scene/pattern_export_spec.hpp"

#include <gtest/gtest.h>

#include "patterns/support/pattern_fixtures.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {
namespace export_spec_test {

const char* const kScene = R"({"body": {"generator": "sphere", "radius": 0.1},
                               "garment": {"cover": {"scale": 0.9}}})";

SceneSpec scene_with_patterns(const nlohmann::json& patterns) {
  nlohmann::json j = nlohmann::json::parse(kScene);
  j["patterns"] = patterns;
  return parse_scene(j, "scene.json", ".");
}

std::string scene_error(const nlohmann::json& patterns) {
  try {
    scene_with_patterns(patterns);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string check_error(const nlohmann::json& patterns) {
  try {
    check_pattern_export_spec(scene_with_patterns(patterns).patterns, test::test_pattern());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PatternExportSpec, DefaultsWithoutASection) {
  const SceneSpec scene = parse_scene(nlohmann::json::parse(kScene), "scene.json", ".");
  const PatternExportOptions defaults;
  EXPECT_EQ(scene.patterns.options.seam_allowance, defaults.seam_allowance);
  EXPECT_EQ(scene.patterns.options.notch_depth, 0.004);
  EXPECT_EQ(scene.patterns.options.true_tolerance, 0.0003);
  EXPECT_TRUE(scene.patterns.options.seam_notch_styles.empty());
  EXPECT_TRUE(scene.patterns.style.empty());
  EXPECT_EQ(scene.patterns.file, "scene.json");
  EXPECT_EQ(scene.patterns.json_path, "/patterns");
}

TEST(PatternExportSpec, ReadsEveryKeyInMetres) {
  const SceneSpec scene = scene_with_patterns(nlohmann::json::parse(R"({
      "seam_allowance": 0.012, "seam_allowances": {"side_left": 0.015, "waist": 0.02},
      "notch_depth": 0.005, "notch_spacing": 0.08, "notches": {"side_right": "double", "side_left": "single"},
      "corner_style": "round", "true_tolerance": 0.0005, "style": "Racer tights", "size": "M"})"));
  const PatternExportOptions& o = scene.patterns.options;
  EXPECT_DOUBLE_EQ(o.seam_allowance, 0.012);
  ASSERT_EQ(o.seam_allowances.size(), 2u);
  EXPECT_DOUBLE_EQ(o.seam_allowances.at("side_left"), 0.015);
  EXPECT_DOUBLE_EQ(o.seam_allowances.at("waist"), 0.02);
  EXPECT_DOUBLE_EQ(o.notch_depth, 0.005);
  EXPECT_DOUBLE_EQ(o.notch_spacing, 0.08);
  EXPECT_EQ(o.seam_notch_styles.at("side_right"), NotchStyle::kDouble);
  EXPECT_EQ(o.seam_notch_styles.at("side_left"), NotchStyle::kSingle);
  EXPECT_EQ(o.corner_style, CornerStyle::kRound);
  EXPECT_DOUBLE_EQ(o.true_tolerance, 0.0005);
  EXPECT_EQ(scene.patterns.style, "Racer tights");
  EXPECT_EQ(scene.patterns.size, "M");
  EXPECT_EQ(check_error(scene.document["patterns"]), "");
}

TEST(PatternExportSpec, BadValuesNameTheFileAndPath) {
  std::string e = scene_error({{"notch_depht", 0.004}});
  EXPECT_NE(e.find("scene.json"), std::string::npos) << e;
  EXPECT_NE(e.find("notch_depht"), std::string::npos) << e;
  e = scene_error({{"notch_depth", -0.001}});
  EXPECT_NE(e.find("scene.json: /patterns/notch_depth"), std::string::npos) << e;
  e = scene_error({{"notches", {{"side_left", "triple"}}}});
  EXPECT_NE(e.find("scene.json: /patterns/notches/side_left"), std::string::npos) << e;
  e = scene_error({{"seam_allowances", {{"side_left", "wide"}}}});
  EXPECT_NE(e.find("scene.json: /patterns/seam_allowances/side_left"), std::string::npos) << e;
  e = scene_error({{"corner_style", "bevel"}});
  EXPECT_NE(e.find("scene.json: /patterns/corner_style"), std::string::npos) << e;
  e = scene_error(nlohmann::json::array());
  EXPECT_NE(e.find("scene.json: /patterns"), std::string::npos) << e;
}

TEST(PatternExportSpec, UnknownSeamNamesNameTheFileAndPath) {
  std::string e = check_error({{"seam_allowances", {{"sleeve_cap", 0.01}}}});
  EXPECT_NE(e.find("scene.json: /patterns/seam_allowances/sleeve_cap"), std::string::npos) << e;
  e = check_error({{"notches", {{"waist", "double"}}}});  // a pinned boundary, not a seam
  EXPECT_NE(e.find("scene.json: /patterns/notches/waist"), std::string::npos) << e;
  EXPECT_EQ(check_error({{"seam_allowances", {{"waist", 0.02}}}}), "");
}

}  // namespace export_spec_test
}  // namespace tightfit
