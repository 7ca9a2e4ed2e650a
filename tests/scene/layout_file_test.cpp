/// A scene's layout given as a file of its own ("garment": {"layout": "file.json"}), and
/// layouts anchored on the skeleton, which take the skeleton and skin weights of the
/// scene's "rig" (garment/layout_anchors.hpp).
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "tightfit/common/error.hpp"
#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::scene_layout_file_test {

namespace fs = std::filesystem;

const fs::path kAnchoredExamples = fs::path(TIGHTFIT_SOURCE_DIR) / "examples";

std::string scene_layout_error(const nlohmann::json& scene) {
  try {
    parse_scene(scene, "leg.json", kAnchoredExamples);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneLayoutFile, ReadsTheLayoutFileTheSceneNames) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_layout_file_" + std::to_string(::getpid()));
  fs::create_directories(dir / "layouts");
  std::ofstream(dir / "layouts" / "halves.json") << R"({
    "dividers": [{"name": "mid", "point": [0, 0, 0], "normal": "left"}],
    "panels": [{"name": "left", "sides": ["+mid"]}, {"name": "right", "sides": ["-mid"]}]})";
  const auto scene = nlohmann::json::parse(
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"layout": "layouts/halves.json"}})");
  const SceneSpec spec = parse_scene(scene, (dir / "scene.json").string(), dir);
  EXPECT_EQ(spec.garment.kind, GarmentKind::kLayout);
  EXPECT_EQ(spec.garment.layout.source, (dir / "layouts" / "halves.json").string());
  ASSERT_EQ(spec.garment.layout.panels.size(), 2u);
  EXPECT_EQ(spec.garment.layout.dividers[0].normal, Vec3::UnitX());
  fs::remove_all(dir);

  EXPECT_EQ(
      scene_layout_error(nlohmann::json::parse(
          R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"layout": "layouts/none.json"}})")),
      "leg.json: /garment/layout: no such file: " +
          (kAnchoredExamples / "layouts" / "none.json").string());
}

TEST(SceneLayoutFile, AnAnchoredLayoutNeedsTheScenesRig) {
  const std::string error = scene_layout_error(nlohmann::json::parse(
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"layout": "layouts/left_leg_anchored.json"}})"));
  EXPECT_EQ(
      error,
      (kAnchoredExamples / "layouts" / "left_leg_anchored.json").string() +
          ": /region/0: anchored on the skeleton or its skin weights, but the scene has no \"rig\" "
          "(\"rig\": {\"mesh\", \"weights\", \"joints\"})");
  const std::string inline_error = scene_layout_error(nlohmann::json::parse(R"({
    "body": {"generator": "sphere", "radius": 0.1},
    "garment": {"layout": {"dividers": [{"name": "mid", "point": {"bone": "root", "at": 0}, "normal": "left"}],
                           "panels": [{"name": "a", "sides": ["+mid"]}, {"name": "b", "sides": ["-mid"]}]}}})"));
  EXPECT_EQ(inline_error.substr(0, inline_error.find(": anchored")),
            "leg.json: /garment/layout/dividers/0");
}

/// The examples lay out one anchored layout file on the legs body and on the child, each
/// with its own rig: load_scene resolves the anchors on each body.
TEST(SceneLayoutFileLoad, OneAnchoredLayoutOnTheManAndTheChild) {
  std::vector<std::vector<std::string>> pieces;
  std::vector<size_t> seams;
  for (const char* name : {"left_leg_anchored_regular.json", "left_leg_anchored_child.json"}) {
    SCOPED_TRACE(name);
    auto scene = load_scene(read_scene(kAnchoredExamples / name));
    ASSERT_TRUE(scene->build.has_value());
    std::vector<std::string> names;
    for (const auto& piece : scene->garment.pattern.pieces) names.push_back(piece.name);
    pieces.push_back(names);
    seams.push_back(scene->build->layout.seams.size());
    EXPECT_EQ(scene->build->layout.pin_names, (std::vector<std::string>{"top", "cuff"}));
  }
  EXPECT_EQ(pieces[0], (std::vector<std::string>{"thigh_front", "thigh_back", "lower_leg_front",
                                                 "lower_leg_back"}));
  EXPECT_EQ(pieces[1], pieces[0]);
  EXPECT_EQ(seams[0], 6u);
  EXPECT_EQ(seams[1], seams[0]);
}

}  // namespace tightfit::scene_layout_file_test
