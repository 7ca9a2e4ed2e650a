#include "tightfit/scene/checkpoint_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/input_file.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"

namespace tightfit {

namespace {

using FileHashes = std::map<std::string, std::string>;

FileHashes hashes_of(const nlohmann::json& inputs) {
  FileHashes files;
  if (!inputs.is_object() || !inputs.contains("files") || !inputs["files"].is_object())
    return files;
  for (auto it = inputs["files"].begin(); it != inputs["files"].end(); ++it)
    if (it.value().is_string()) files[it.key()] = it.value().get<std::string>();
  return files;
}

/// Removes from `a` and `b` the entries they share: same path and hash, or (a file moved)
/// the same hash under another path.
void drop_shared(FileHashes& a, FileHashes& b) {
  for (auto it = a.begin(); it != a.end();) {
    auto same = b.find(it->first);
    if (same == b.end() || same->second != it->second)
      same =
          std::find_if(b.begin(), b.end(), [&](const auto& e) { return e.second == it->second; });
    if (same != b.end() && same->second == it->second) {
      b.erase(same);
      it = a.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace

nlohmann::json run_inputs_json(std::uint64_t since, nlohmann::json scene,
                               const std::string& scene_key) {
  nlohmann::json files = nlohmann::json::object();
  for (const auto& [path, hash] : input_files_read(since)) files[path] = hash;
  if (scene.is_object()) {
    scene.erase("description");
    if (scene.contains("optimize") && scene["optimize"].is_object())
      for (const char* key : {"max_iterations", "checkpoint_every", "time_limit"})
        scene["optimize"].erase(key);
  }
  files[scene_key] = "scene " + content_hash(scene.dump());
  return {{"files", files}};
}

nlohmann::json run_inputs_json(std::uint64_t since, const std::string& scene_file) {
  std::error_code ec;
  std::filesystem::path key = std::filesystem::weakly_canonical(scene_file, ec);
  if (ec) key = std::filesystem::absolute(scene_file);
  return run_inputs_json(since, read_json_file(scene_file), key.string());
}

void check_same_inputs(const nlohmann::json& recorded, const nlohmann::json& now,
                       const std::filesystem::path& checkpoint_file) {
  if (recorded.is_null()) return;  // an older version's checkpoint: nothing to compare
  FileHashes before = hashes_of(recorded), after = hashes_of(now);
  drop_shared(before, after);
  if (before.empty() && after.empty()) return;
  const std::string intro = "was written for other inputs than this run's: ";
  const std::string outro =
      " (resume with the scene and files the checkpoint was written for, or start a new run "
      "without --resume)";
  for (const auto& [path, hash] : after)
    if (before.contains(path))
      throw InputError(checkpoint_file.string(), intro + path + " changed since (content hash " +
                                                     before[path] + " then, " + hash + " now)" +
                                                     outro);
  if (!after.empty())
    throw InputError(checkpoint_file.string(), intro + "this run reads " + after.begin()->first +
                                                   ", the checkpointed run did not" + outro);
  throw InputError(
      checkpoint_file.string(),
      intro + "the checkpointed run read " + before.begin()->first + ", this run does not" + outro);
}

void check_checkpoint_coordinates(const OptimizationCheckpoint& c,
                                  const std::filesystem::path& checkpoint_file) {
  auto check = [&](double v, const std::string& what) {
    if (std::abs(v) > kMaxCoordinate)
      throw InputError(checkpoint_file.string(),
                       what + " is " + format_number(v) + " m: more than " +
                           format_number(kMaxCoordinate) +
                           " m from the origin, not a coordinate of a garment or a body");
  };
  for (Eigen::Index i = 0; i < c.parameters.size(); ++i)
    check(c.parameters[i], "/parameters/" + std::to_string(i));
  for (Eigen::Index i = 0; i < c.state.body.rows(); ++i)
    for (Eigen::Index k = 0; k < 3; ++k)
      check(c.state.body(i, k), "/state/body/" + std::to_string(i) + "/" + std::to_string(k));
}

void write_checkpoint_with_inputs(const std::filesystem::path& file,
                                  const OptimizationCheckpoint& c,
                                  const std::vector<std::string>& term_names,
                                  const nlohmann::json& inputs) {
  nlohmann::json j = checkpoint_json(c, term_names);
  j["inputs"] = inputs;
  write_json_atomically(file, j);
}

OptimizationCheckpoint read_checkpoint_for(const std::filesystem::path& file,
                                           const std::vector<std::string>& term_names,
                                           const nlohmann::json* inputs) {
  nlohmann::json j = read_json_file(file.string());
  nlohmann::json recorded;
  if (j.is_object() && j.contains("inputs")) {
    recorded = j["inputs"];
    j.erase("inputs");
  }
  if (inputs != nullptr) check_same_inputs(recorded, *inputs, file);
  OptimizationCheckpoint c = checkpoint_from_json(j, term_names, file.string());
  check_checkpoint_coordinates(c, file);
  return c;
}

}  // namespace tightfit
