// The scene's "measurements" (the ease table's levels) and the skeleton they are placed on.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {
namespace scene_measurements_test {

/// A scene on the legs body with the regular man's joints as the body's skeleton, with
/// `measurements` (JSON text) appended; parsed against the source folder.
SceneSpec legs_scene(const std::string& measurements) {
  std::string text = R"({"body": {"mesh": "data/bodies/mh_legs_male.obj",
                                  "skeleton": "data/rig/mh_male_regular.joints.json"},
                         "garment": {"cover": {"scale": 0.9}})";
  if (!measurements.empty()) {
    text += R"(, "measurements": )";
    text += measurements;
  }
  text += "}";
  return parse_scene(nlohmann::json::parse(text), "scene.json", TIGHTFIT_SOURCE_DIR);
}

std::string error_of(const std::string& measurements) {
  try {
    legs_scene(measurements);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// 0 when `scene` (JSON text) validates against schema/scene.schema.json.
int schema_check(const std::string& scene, const std::string& tag) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("tightfit_measurements_" + tag + "_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << scene;
  std::string cmd =
      "/usr/bin/python3 -c \"import json,sys,jsonschema; "
      "jsonschema.validate(json.load(open(sys.argv[2])), json.load(open(sys.argv[1])))\" '";
  cmd += TIGHTFIT_SOURCE_DIR;
  cmd += "/schema/scene.schema.json' '";
  cmd += file.string();
  cmd += "' 2>/dev/null";
  const int status = std::system(cmd.c_str());
  std::filesystem::remove(file);
  return status;
}

}  // namespace scene_measurements_test

using namespace scene_measurements_test;

TEST(SceneMeasurements, LevelsOnBonesAndInAbsoluteCoordinates) {
  const SceneSpec s = legs_scene(R"([
      {"name": "calf", "point": {"bone": "lowerleg01.L", "at": 0.45}, "normal": "along_bone"},
      {"name": "knee height", "point": [0.1, 0.5, 0.02], "normal": "up"}])");
  ASSERT_TRUE(s.measurements_given);
  ASSERT_EQ(s.measurements.size(), 2u);
  ASSERT_TRUE(s.skeleton);
  EXPECT_NE(s.skeleton_source.find("mh_male_regular.joints.json"), std::string::npos);
  const auto joints =
      read_skeleton(std::string(TIGHTFIT_SOURCE_DIR) + "/data/rig/mh_male_regular.joints.json");
  const BoneSegment& shin = joints.at("lowerleg01.L");
  const MeasurementLevel& calf = s.measurements[0];
  EXPECT_EQ(calf.name, "calf");
  EXPECT_EQ(calf.origin, "scene");
  EXPECT_EQ(calf.anchor, "lowerleg01.L at 0.45");
  EXPECT_LT((calf.point - (shin.head + 0.45 * (shin.tail - shin.head))).norm(), 1e-12);
  EXPECT_LT((calf.normal - (shin.tail - shin.head).normalized()).norm(), 1e-12);
  const MeasurementLevel& knee = s.measurements[1];
  EXPECT_EQ(knee.point, Vec3(0.1, 0.5, 0.02));
  EXPECT_EQ(knee.normal, Vec3::UnitY());
  EXPECT_EQ(knee.anchor, "point");
  // Without the key the outputs choose the levels; an empty list turns the table off.
  EXPECT_FALSE(legs_scene("").measurements_given);
  const SceneSpec off = legs_scene("[]");
  EXPECT_TRUE(off.measurements_given);
  EXPECT_TRUE(off.measurements.empty());
}

TEST(SceneMeasurements, MistakesNameTheFileAndJsonPath) {
  EXPECT_EQ(
      error_of(
          R"([{"name": "calf", "point": {"bone": "shin.L", "at": 0.5}, "normal": "along_bone"}])")
          .rfind("scene.json: /measurements/0/point/bone: unknown bone \"shin.L\"", 0),
      0u);
  EXPECT_EQ(error_of(R"([{"name": "a", "point": [0, 0.5, 0], "normal": "up"},
                        {"name": "a", "point": [0, 0.6, 0], "normal": "up"}])"),
            "scene.json: /measurements/1/name: a second level named \"a\"");
  EXPECT_EQ(error_of(R"([{"point": [0, 0.5, 0], "normal": "up"}])"),
            "scene.json: /measurements/0/name: missing (expected a string)");
  EXPECT_EQ(error_of(R"([{"name": "a", "point": [0, 0.5, 0], "normal": [0, 0, 0]}])"),
            "scene.json: /measurements/0/normal: the normal must not be zero");
  EXPECT_EQ(error_of(R"([{"name": "a", "point": [0, 0.5, 0], "normal": "up", "height": 1}])"),
            "scene.json: /measurements/0/height: unknown key \"height\"");
  EXPECT_EQ(error_of(R"({"name": "a"})"),
            "scene.json: /measurements: expected an array of objects, got object");
  EXPECT_EQ(error_of("null"), "scene.json: /measurements: expected an array of objects, got null");
  // Bones without a skeleton.
  const std::string text =
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {}},
      "measurements": [{"name": "calf", "point": {"bone": "lowerleg01.L", "at": 0.45}, "normal": "along_bone"}]})";
  std::string error = "no error";
  try {
    parse_scene(nlohmann::json::parse(text), "bad.json", ".");
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_EQ(
      error.rfind("bad.json: /measurements/0: anchored on the skeleton, but there is none", 0), 0u)
      << error;
}

TEST(SceneMeasurements, TheSchemaKnowsTheKey) {
  const std::string base =
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {}}, )";
  std::string good = base;
  good +=
      R"("measurements": [{"name": "calf", "point": {"bone": "lowerleg01.L", "at": 0.45}, "normal": "along_bone"},
                              {"name": "y", "point": [0, 0.5, 0], "normal": [0, 1, 0]}]})";
  EXPECT_EQ(schema_check(good, "good"), 0);
  std::string bad = base;
  bad += R"("measurements": [{"name": "calf", "point": [0, 0.5, 0], "normal": "sideways"}]})";
  EXPECT_NE(schema_check(bad, "bad"), 0);
  std::string unnamed = base;
  unnamed += R"("measurements": [{"point": [0, 0.5, 0], "normal": "up"}]})";
  EXPECT_NE(schema_check(unnamed, "unnamed"), 0);
}

}  // namespace tightfit
