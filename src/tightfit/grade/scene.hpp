#pragma once
/// The design of `tightfit grade` and the scene of each body made from it: the design
/// scene's body mesh and rig are replaced at the JSON document level, so that each body
/// runs exactly the scene `tightfit optimize` would run (its "optimize" section, its
/// layout, materials and solver settings).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tightfit/grade/bodies.hpp"

namespace tightfit {

/// A design scene as read (validated per body, when each body's scene is parsed).
struct GradeDesign {
  std::filesystem::path file;
  nlohmann::json document;
};

/// Reads the design scene: a JSON object with an "optimize" section, a "rig" with
/// "mesh", "weights" and "joints", and either no "body" (each body is then its mesh with
/// the default settings) or a "body" with a "mesh" (replaced by each body's; its other
/// settings apply to every body). The "optimize" section is checked here
/// (parse_optimization_spec): it is the same for every body. InputError naming the file
/// and what is wrong.
GradeDesign read_grade_design(const std::filesystem::path& file);

/// The keys whose string values are file paths in a scene (body mesh, core skeleton,
/// layout file, rig files, pose BVH files, shape target, fabric file).
bool is_scene_path_key(const std::string& key);

/// The scene of `design` on `body`, to be written as a file in folder `scene_dir`:
/// /body/mesh is the body's mesh (/body is made when the design has none), /rig/joints its joints,
/// /rig/mesh its rig mesh (and /pressure/rig/mesh when the design has a pressure rig); every other
/// relative path (is_scene_path_key) is rewritten relative to `scene_dir` so that it names the same
/// file as in the design. Paths are written relative to `scene_dir` when both lie under
/// one folder, else absolute.
nlohmann::json grade_body_scene(const GradeDesign& design, const GradeBody& body,
                                const std::filesystem::path& scene_dir);

/// Hex digest (64-bit FNV-1a) of `scene` (compact JSON text), of the content of every
/// file it names (paths resolved against `scene_dir`; a missing file counts by its
/// name) and of `extra`: equal digests mean equal inputs of a body's run.
std::string grade_fingerprint(const nlohmann::json& scene, const std::filesystem::path& scene_dir,
                              const std::string& extra);

}  // namespace tightfit
