#include "tightfit/grade/scene.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>

#include "tightfit/common/error.hpp"
#include "tightfit/common/input_file.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/design/optimization_spec.hpp"

namespace tightfit {
namespace {

namespace fs = std::filesystem;

/// `file` (absolute, normalized) as written into a scene in `scene_dir`.
std::string scene_path(const fs::path& file, const fs::path& scene_dir) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  const fs::path dir = fs::absolute(scene_dir).lexically_normal();
  const fs::path relative = absolute.lexically_relative(dir);
  return relative.empty() ? absolute.string() : relative.string();
}

/// Rewrites every relative path of `node` (resolved against `from`) for a scene in `to`.
void rebase_paths(nlohmann::json& node, const fs::path& from, const fs::path& to) {
  if (node.is_array()) {
    for (auto& item : node) rebase_paths(item, from, to);
    return;
  }
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (it.value().is_string() && is_scene_path_key(it.key())) {
      const fs::path p(it.value().get<std::string>());
      if (!p.empty() && p.is_relative()) it.value() = scene_path(from / p, to);
    } else {
      rebase_paths(it.value(), from, to);
    }
  }
}

/// Every file path of `node` (is_scene_path_key), resolved against `dir`.
void collect_paths(const nlohmann::json& node, const fs::path& dir, std::set<fs::path>& out) {
  if (node.is_array()) {
    for (const auto& item : node) collect_paths(item, dir, out);
    return;
  }
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (it.value().is_string() && is_scene_path_key(it.key())) {
      const fs::path p(it.value().get<std::string>());
      out.insert((p.is_relative() ? dir / p : p).lexically_normal());
    } else {
      collect_paths(it.value(), dir, out);
    }
  }
}

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(data[i]);
      h *= 1099511628211ull;
    }
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }  // with the terminator
};

}  // namespace

bool is_scene_path_key(const std::string& key) {
  static const std::set<std::string> keys = {"mesh",   "weights", "joints", "skeleton",
                                             "layout", "bvh",     "target", "fabric"};
  return keys.contains(key);
}

GradeDesign read_grade_design(const fs::path& file) {
  const std::string source = file.string();
  GradeDesign design{file, read_json_file(source)};
  const nlohmann::json& d = design.document;
  if (!d.is_object()) throw InputError(source, "expected a scene (a JSON object)");
  if (!d.contains("optimize") || !d["optimize"].is_object())
    throw InputError(source,
                     "a design needs an \"optimize\" section: grading optimizes the "
                     "design on every body");
  if (d.contains("body") &&
      (!d["body"].is_object() || !d["body"].contains("mesh") || !d["body"]["mesh"].is_string()))
    throw InputError(source,
                     "/body: a design's body must be a \"mesh\" (each body of the bodies "
                     "file replaces it; its other settings — edge length, crop, core — "
                     "apply to every body), or leave \"body\" out");
  if (!d.contains("rig") || !d["rig"].is_object())
    throw InputError(source,
                     "a design needs a \"rig\" {\"mesh\", \"weights\", \"joints\"}: "
                     "each body brings its own joints (and rig mesh)");
  for (const char* key : {"mesh", "weights", "joints"})
    if (!d["rig"].contains(key) || !d["rig"][key].is_string())
      throw InputError(source, std::string("/rig/") + key + ": expected a file name");
  // The same for every body: a mistake there is the design's, found before any body runs.
  parse_optimization_spec(d["optimize"], source, "/optimize", file.parent_path());
  return design;
}

nlohmann::json grade_body_scene(const GradeDesign& design, const GradeBody& body,
                                const fs::path& scene_dir) {
  nlohmann::json scene = design.document;
  rebase_paths(scene, design.file.parent_path(), scene_dir);
  if (!scene.contains("body")) scene["body"] = nlohmann::json::object();
  scene["body"]["mesh"] = scene_path(body.mesh, scene_dir);
  scene["rig"]["joints"] = scene_path(body.joints, scene_dir);
  scene["rig"]["mesh"] = scene_path(body.rig_mesh, scene_dir);
  if (scene.contains("pressure") && scene["pressure"].is_object() &&
      scene["pressure"].contains("rig") && scene["pressure"]["rig"].is_object())
    scene["pressure"]["rig"]["mesh"] = scene_path(body.rig_mesh, scene_dir);
  const std::string note =
      "grading body \"" + body.name + "\" of design " + design.file.filename().string();
  scene["description"] = scene.contains("description") && scene["description"].is_string()
                             ? scene["description"].get<std::string>() + " (" + note + ")"
                             : note;
  return scene;
}

std::string grade_fingerprint(const nlohmann::json& scene, const fs::path& scene_dir,
                              const std::string& extra) {
  Fnv1a hash;
  hash.add(scene.dump());
  hash.add(extra);
  std::set<fs::path> files;
  collect_paths(scene, scene_dir, files);
  for (const fs::path& file : files) {
    hash.add(file.filename().string());
    try {
      const std::string bytes = read_input_file(file);  // a regular file, of bounded size
      hash.add(bytes.data(), bytes.size());
    } catch (const InputError&) {
      // not readable: the run that reads it says why
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash.h));
  return text;
}

}  // namespace tightfit
