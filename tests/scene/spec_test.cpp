#include "tightfit/scene/spec.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tightfit/common/error.hpp"

namespace tightfit::scene_spec_test {

const std::filesystem::path kExamples = std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "examples";

std::vector<std::filesystem::path> example_scenes() {
  std::vector<std::filesystem::path> out;
  for (const auto& e : std::filesystem::directory_iterator(kExamples))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SceneSpec, EveryExampleParses) {
  const auto scenes = example_scenes();
  ASSERT_GE(scenes.size(), 3u);
  for (const auto& file : scenes) EXPECT_NO_THROW(read_scene(file)) << file;
}

std::string error_of(const std::string& text);

/// Validates `file` against the schema's definition `def` ("" for a whole scene).
int validate(const std::filesystem::path& file, const std::string& def = "") {
  const std::string schema = std::string(TIGHTFIT_SOURCE_DIR) + "/schema/scene.schema.json";
  const std::string cmd =
      "/usr/bin/python3 -c \"import json,sys,jsonschema; s = json.load(open(sys.argv[1])); "
      "d = sys.argv[3]; s = {'\\$ref': '#/\\$defs/' + d, '\\$defs': s['\\$defs']} if d else s; "
      "jsonschema.Draft202012Validator(s).validate(json.load(open(sys.argv[2])))\" '" +
      schema + "' '" + file.string() + "' '" + def + "'";
  return std::system(cmd.c_str());
}

TEST(SceneSpec, EveryExampleValidatesAgainstTheSchema) {
  std::vector<std::filesystem::path> scenes = example_scenes();
  scenes.push_back(kExamples / "grading/left_leg.json");
  for (const auto& e : std::filesystem::directory_iterator(
           std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "tests/scene/data/schema_corpus"))
    if (e.path().extension() == ".json") scenes.push_back(e.path());
  for (const auto& file : scenes) EXPECT_EQ(validate(file), 0) << file;
}

TEST(SceneSpec, EveryLayoutFileValidatesAgainstTheSchema) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(kExamples / "layouts")) {
    EXPECT_EQ(validate(e.path(), "layout"), 0) << e.path();
    ++files;
  }
  EXPECT_GE(files, 2);
}

TEST(SceneSpec, TheSchemaRejectsWhatTheReaderRejects) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "tightfit_schema_test";
  std::filesystem::create_directories(dir);
  const auto rejected = [&](const std::string& text) {
    const std::filesystem::path file = dir / "scene.json";
    std::ofstream(file) << text;
    EXPECT_NE(error_of(text), "") << text;
    return validate(file) != 0;
  };
  EXPECT_TRUE(rejected(
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {"scal": 1}}})"));
  EXPECT_TRUE(rejected(
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {}, "sleeve": {}}})"));
  EXPECT_TRUE(rejected(
      R"({"body": {"generator": "sphere", "radius": 0.1, "mesh": "a.obj"}, "garment": {"cover": {}}})"));
  EXPECT_TRUE(rejected(
      R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {}}, "fabric": {"poisson_ratio": 1.5}})"));
  std::filesystem::remove_all(dir);
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(nlohmann::json::parse(text), "bad.json", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kGood =
    R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {"scale": 0.9}}})";

TEST(SceneSpec, ASleeveEdgeTooShortToMeshIsAnErrorBeforeMeshing) {
  const std::string e =
      error_of(R"({"body": {"generator": "cylinder", "radius": 0.05, "length": 0.3},
                                    "garment": {"sleeve": {"edge_length": 0.00001}}})");
  EXPECT_NE(
      e.find(
          "bad.json: /garment/sleeve/edge_length: an edge length of 1e-05 m would mesh the sleeve"),
      std::string::npos)
      << e;
}

TEST(SceneSpec, ReadsMaterialsAndDefaults) {
  auto j = nlohmann::json::parse(kGood);
  j["fabric"] = {{"youngs_modulus", 30e6}, {"thickness", 2e-4}};
  j["body_material"] = {{"rigid", true}};
  j["pressure"] = {{"shape_operator", "limit_surface"}};
  const SceneSpec s = parse_scene(j, "s.json", ".");
  EXPECT_EQ(s.garment.kind, GarmentKind::kCover);
  EXPECT_DOUBLE_EQ(s.materials.fabric.youngs_modulus, 30e6);
  EXPECT_DOUBLE_EQ(s.materials.fabric.poisson_ratio, 0.33);
  EXPECT_TRUE(s.materials.rigid_body);
  EXPECT_EQ(s.pressure_operator, ShapeOperatorKind::kLimitSurface);
}

TEST(SceneSpec, ErrorsNameTheFileAndJsonPath) {
  auto with = [](const std::string& key, const nlohmann::json& value) {
    auto j = nlohmann::json::parse(kGood);
    j[key] = value;
    return j.dump();
  };
  EXPECT_EQ(error_of(with("fabric", {{"youngs_modulus", "stiff"}})),
            "bad.json: /fabric/youngs_modulus: expected a number, got string");
  EXPECT_EQ(error_of(with("fabrik", nlohmann::json::object())),
            "bad.json: /fabrik: unknown key \"fabrik\"");
  EXPECT_NE(error_of(with("fabric", {{"poisson_ratio", 1.5}})).find("/fabric/poisson_ratio"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {}})")
                .find("/garment"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"garment": {"cover": {}}})").find("/body: missing"), std::string::npos);
  EXPECT_NE(
      error_of(
          R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"cover": {}, "sleeve": {}}})")
          .find("exactly one"),
      std::string::npos);
  EXPECT_NE(
      error_of(
          R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": {"sleeve": {"radius": -1}}})")
          .find("/garment/sleeve/radius"),
      std::string::npos);
}

TEST(SceneSpec, NullsAndPhysicsBeyondReasonAreErrorsNamingTheJsonPath) {
  auto with = [](const std::string& key, const nlohmann::json& value) {
    auto j = nlohmann::json::parse(kGood);
    j[key] = value;
    return j.dump();
  };
  EXPECT_EQ(error_of(R"({"body": null, "garment": {"cover": {}}})"),
            "bad.json: /body: is null (expected an object)");
  EXPECT_EQ(error_of(R"({"body": {"generator": "sphere", "radius": 0.1}, "garment": null})"),
            "bad.json: /garment: is null (expected an object)");
  for (const char* section : {"fabric", "body_material", "patterns", "solver"})
    EXPECT_NE(error_of(with(section, nullptr)).find(std::string("/") + section + ": is null"),
              std::string::npos)
        << section;
  EXPECT_EQ(error_of(with("fabric", {{"youngs_modulus", 1e308}})),
            "bad.json: /fabric/youngs_modulus: is 1e+308, beyond ±1e+15 (no quantity of a scene "
            "in SI units is that large)");
  EXPECT_NE(error_of(with("body_material", {{"youngs_modulus", 1e14}}))
                .find("/body_material/youngs_modulus: is 1e+14, more than 1e+12"),
            std::string::npos);
  EXPECT_NE(error_of(with("solver", {{"max_iterations", 4294967296}}))
                .find("/solver/max_iterations: is 4294967296, out of range"),
            std::string::npos);
}

}  // namespace tightfit::scene_spec_test
