// The scene schema (schema/scene.schema.json) against the scene readers: every key a
// reader asks for, at its JSON path, is a property of the schema there; the scenes parsed
// reach every key the readers name; and every property of the schema is read.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/json_key_observer.hpp"
#include "tightfit/design/optimization_spec.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::schema_coverage_test {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource(TIGHTFIT_SOURCE_DIR);

/// Sources whose JsonFields read scene keys (the scene, its layout file, its optimize section).
const std::set<std::string> kSceneReaders = {"src/tightfit/scene/spec.cpp",
                                             "src/tightfit/scene/fabric_spec.cpp",
                                             "src/tightfit/scene/pattern_export_spec.cpp",
                                             "src/tightfit/scene/poses.cpp",
                                             "src/tightfit/design/optimization_spec.cpp",
                                             "src/tightfit/garment/layout_spec.cpp",
                                             "src/tightfit/garment/measurement_levels.cpp",
                                             "src/tightfit/garment/pattern_options.cpp",
                                             "src/tightfit/objectives/pressure_region.cpp",
                                             "src/tightfit/body/body_spec.cpp",
                                             "src/tightfit/body/skeleton_anchor.cpp"};

/// Sources whose JsonFields read other files (joints, saved states, pieces.json, bodies).
const std::set<std::string> kOtherReaders = {"src/tightfit/common/json_fields.cpp",
                                             "src/tightfit/body/skeleton.cpp",
                                             "src/tightfit/scene/optimization_checkpoint.cpp",
                                             "src/tightfit/scene/pattern_record.cpp",
                                             "src/tightfit/patterns/json.cpp",
                                             "src/tightfit/grade/bodies.cpp",
                                             "src/tightfit/scene/run_state.cpp"};

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The scenes parsed: the examples, the grading design and the scenes written for this test.
std::vector<fs::path> corpus() {
  std::vector<fs::path> out;
  for (const fs::path& dir : {kSource / "examples", kSource / "examples/grading",
                              kSource / "tests/scene/data/schema_corpus"})
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json" && e.path().filename() != "bodies_full.json")
        out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// A key asked for by a reader: the scene file and the JSON path of its object.
struct Asked {
  std::string scene;
  std::string path;
  std::string key;
};

/// Parses every scene of the corpus (and its optimize section) and records the keys asked
/// for in the scene and in its layout file (whose keys are those of /garment/layout).
std::vector<Asked> asked_keys() {
  std::vector<Asked> out;
  for (const fs::path& file : corpus()) {
    const json document = read_json_file(file.string());
    std::map<std::string, std::string> prefix = {{file.string(), ""}};
    if (document.contains("garment") && document["garment"].contains("layout") &&
        document["garment"]["layout"].is_string())
      prefix[(file.parent_path() / document["garment"]["layout"].get<std::string>()).string()] =
          "/garment/layout";
    ScopedJsonKeyObserver observer(
        [&](const std::string& source, const std::string& path, const std::string& key) {
          if (const auto it = prefix.find(source); it != prefix.end())
            out.push_back({file.filename().string(), it->second + path, key});
        });
    const SceneSpec scene = read_scene(file);
    if (scene.optimize.is_object())
      parse_optimization_spec(scene.optimize, file.string(), "/optimize", scene.base_dir);
  }
  return out;
}

const std::vector<Asked>& recorded() {
  static const std::vector<Asked> keys = asked_keys();
  return keys;
}

const json& schema() {
  static const json s = read_json_file((kSource / "schema/scene.schema.json").string());
  return s;
}

/// The node and the schemas it defers to ($ref, oneOf, anyOf, allOf), recursively.
void branches(const json& node, std::vector<const json*>& out) {
  if (!node.is_object()) return;
  out.push_back(&node);
  if (node.contains("$ref"))
    branches(schema().at(json::json_pointer(node["$ref"].get<std::string>().substr(1))), out);
  for (const char* k : {"oneOf", "anyOf", "allOf"})
    if (node.contains(k))
      for (const json& b : node[k]) branches(b, out);
}

std::vector<const json*> branches_of(const std::vector<const json*>& nodes) {
  std::vector<const json*> out;
  for (const json* n : nodes) branches(*n, out);
  return out;
}

/// The schemas of member `token` (an object key or an array index) of a value of `nodes`.
std::vector<const json*> member(const std::vector<const json*>& nodes, const std::string& token) {
  const bool index = !token.empty() && std::all_of(token.begin(), token.end(), ::isdigit);
  std::vector<const json*> out;
  for (const json* b : branches_of(nodes)) {
    if (index && b->contains("items")) out.push_back(&(*b)["items"]);
    if (b->contains("properties") && (*b)["properties"].contains(token))
      out.push_back(&(*b)["properties"][token]);
    else if (b->contains("additionalProperties") && (*b)["additionalProperties"].is_object())
      out.push_back(&(*b)["additionalProperties"]);
  }
  return out;
}

std::vector<const json*> schema_at(const std::string& path) {
  std::vector<const json*> nodes = {&schema()};
  std::stringstream tokens(path);
  std::string token;
  while (std::getline(tokens, token, '/'))
    if (!token.empty()) nodes = member(nodes, token);
  return nodes;
}

TEST(SceneSchema, EveryKeyAReaderAsksForIsInTheSchemaAtItsPath) {
  ASSERT_GT(recorded().size(), 500u);
  std::set<std::string> reported;
  for (const Asked& a : recorded()) {
    if (!member(schema_at(a.path), a.key).empty()) continue;
    const std::string where = a.path + "/" + a.key;
    if (!reported.insert(std::regex_replace(where, std::regex("/[0-9]+"), "/*")).second) continue;
    ADD_FAILURE() << a.scene << ": the readers ask for " << where
                  << ", which schema/scene.schema.json does not describe";
  }
}

/// "KEY" of every JsonFields getter called with a literal key in `text`, with its line.
std::vector<std::pair<std::string, int>> literal_keys(const std::string& text) {
  static const std::regex call(
      R"(\.(number|positive|integer|boolean|string|choice|vec3|vec2|object|objects|raw|has)\(\s*"([^"]+)\")");
  std::vector<std::pair<std::string, int>> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), call); it != std::sregex_iterator();
       ++it) {
    const auto at = static_cast<std::ptrdiff_t>(it->position(0));
    out.emplace_back((*it)[2].str(), 1 + std::count(text.begin(), text.begin() + at, '\n'));
  }
  return out;
}

TEST(SceneSchema, EveryReaderOfJsonFieldsIsKnown) {
  for (const auto& e : fs::recursive_directory_iterator(kSource / "src")) {
    if (e.path().extension() != ".cpp") continue;
    const std::string rel = fs::relative(e.path(), kSource).generic_string();
    if (read_text(e.path()).find("JsonFields") == std::string::npos) continue;
    EXPECT_TRUE(kSceneReaders.contains(rel) || kOtherReaders.contains(rel))
        << rel << " reads JSON with JsonFields: list it in kSceneReaders (it reads scene keys, "
        << "which schema/scene.schema.json must describe) or in kOtherReaders";
  }
}

TEST(SceneSchema, TheScenesParsedReachEveryKeyTheSceneReadersName) {
  std::set<std::string> reached;
  for (const Asked& a : recorded()) reached.insert(a.key);
  int named = 0;
  for (const std::string& rel : kSceneReaders)
    for (const auto& [key, line] : literal_keys(read_text(kSource / rel))) {
      ++named;
      EXPECT_TRUE(reached.contains(key))
          << rel << ":" << line << ": key \"" << key
          << "\" is read, but no scene of examples/ or tests/scene/data/schema_corpus/ "
             "reaches it: add one there, so that its place in the schema is checked";
    }
  EXPECT_GT(named, 150);
}

/// Every property name of the schema, with the JSON pointer of its definition.
void property_names(const json& node, const std::string& where,
                    std::map<std::string, std::string>& out) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (it.key() == "properties" && it.value().is_object())
        for (auto p = it.value().begin(); p != it.value().end(); ++p)
          out.emplace(p.key(), where + "/properties/" + p.key());
      property_names(it.value(), where + "/" + it.key(), out);
    }
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      property_names(node[i], where + "/" + std::to_string(i), out);
  }
}

TEST(SceneSchema, EveryKeyOfTheSchemaIsRead) {
  std::set<std::string> reached;
  for (const Asked& a : recorded()) reached.insert(a.key);
  std::map<std::string, std::string> names;
  property_names(schema(), "#", names);
  for (const auto& [name, where] : names)
    EXPECT_TRUE(reached.contains(name))
        << where << ": no reader asks for \"" << name << "\" in any scene parsed";
}

/// Every number of the schema says its unit ("x-unit": "1" when dimensionless).
void numbers_without_unit(const json& node, const std::string& where,
                          std::vector<std::string>& out) {
  if (node.is_object()) {
    if (node.contains("description") && node.value("type", json()) == "number" &&
        !node.contains("x-unit"))
      out.push_back(where);
    for (auto it = node.begin(); it != node.end(); ++it)
      numbers_without_unit(it.value(), where + "/" + it.key(), out);
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      numbers_without_unit(node[i], where + "/" + std::to_string(i), out);
  }
}

TEST(SceneSchema, EveryNumberHasAUnit) {
  std::vector<std::string> missing;
  numbers_without_unit(schema(), "#", missing);
  EXPECT_TRUE(missing.empty()) << missing.front() << " and " << missing.size() - 1 << " more";
}

}  // namespace tightfit::schema_coverage_test
