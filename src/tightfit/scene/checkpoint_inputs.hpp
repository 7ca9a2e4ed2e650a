#pragma once
/// The inputs a run's checkpoint records, and what `optimize --resume` checks before it continues
/// from a checkpoint: that the checkpoint was written for the same inputs (the scene and every file
/// it read, by a hash of their bytes) and holds coordinates of a garment and a body.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

/// {"files": {absolute path: content hash}}: the inputs this run read after the first
/// `since` reads (common/input_file.hpp), recorded in every checkpoint as "inputs". The
/// scene document `scene` counts under `scene_key` (for a file: its absolute path) by
/// its content without the settings a resumed run may change (description,
/// optimize/max_iterations, optimize/checkpoint_every, optimize/time_limit).
nlohmann::json run_inputs_json(std::uint64_t since, nlohmann::json scene,
                               const std::string& scene_key);
/// The same for the scene file `scene_file` (read again; its key is its canonical path).
nlohmann::json run_inputs_json(std::uint64_t since, const std::string& scene_file);

/// Throws InputError naming `checkpoint_file` when the inputs recorded in it (`recorded`,
/// its "inputs" member; null for a checkpoint of an older version, which is not checked)
/// differ from `now`: it names the first file that changed, or that only one of the two
/// runs read. A file moved or renamed with the same bytes is the same input.
void check_same_inputs(const nlohmann::json& recorded, const nlohmann::json& now,
                       const std::filesystem::path& checkpoint_file);

/// Writes the checkpoint (scene/optimization_checkpoint.hpp) with `inputs` (from
/// run_inputs_json) as its member "inputs", atomically.
void write_checkpoint_with_inputs(const std::filesystem::path& file,
                                  const OptimizationCheckpoint& c,
                                  const std::vector<std::string>& term_names,
                                  const nlohmann::json& inputs);

/// Reads the checkpoint `file` of a run with `term_names`, refusing it (InputError naming
/// the file) when its coordinates are absurd (check_checkpoint_coordinates) or, unless
/// `inputs` is null, when its recorded inputs differ from `*inputs` (check_same_inputs).
OptimizationCheckpoint read_checkpoint_for(const std::filesystem::path& file,
                                           const std::vector<std::string>& term_names,
                                           const nlohmann::json* inputs);

/// Throws InputError naming `checkpoint_file` when a design parameter or body coordinate
/// lies more than kMaxCoordinate (common/json_fields.hpp) from the origin.
void check_checkpoint_coordinates(const OptimizationCheckpoint& c,
                                  const std::filesystem::path& checkpoint_file);

}  // namespace tightfit
