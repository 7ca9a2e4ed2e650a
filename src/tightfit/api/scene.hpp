#pragma once
/// A scene of the public API: a scene file (or JSON document) read and validated, then
/// loaded — the body, its limit surface, the garment on it — and its simulation. A thin
/// layer over scene/spec.hpp (read_scene, parse_scene), scene/loader.hpp (load_scene,
/// make_simulation) and scene/optimization_setup.hpp (the "optimize" section).
///
/// Reading is cheap and checks the whole document (InputError naming the file and the
/// JSON path), so that a front-end can refuse bad input before it prepares anything
/// else; loading (seconds to minutes for a full body) happens at load() or at the first
/// call that needs it.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/optimization_setup.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::api {

/// Newton's progress: called after each accepted step of a forward solve with the step
/// and the seconds since that solve began.
using NewtonStepCallback = std::function<void(const NewtonIteration& step, double seconds)>;

class Scene {
 public:
  /// Reads and validates the scene file `file` (read_scene). Nothing is loaded yet.
  static Scene read(const std::filesystem::path& file);
  /// Validates the scene document `document` (parse_scene); `name` stands for the file in
  /// messages and outputs (e.g. "scene.json"), `base_dir` is the folder its relative
  /// paths (body mesh, layout mesh, shape target) resolve against.
  static Scene from_json(const nlohmann::json& document, const std::string& name,
                         const std::filesystem::path& base_dir = ".");

  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  /// The scene file (or the name given to from_json).
  const std::string& file() const { return spec().file; }
  /// The validated scene (after loading: the loaded scene's).
  const SceneSpec& spec() const;

  /// Whether the scene has an "optimize" section.
  bool has_optimization() const { return !spec().optimize.is_null(); }
  /// The parsed "optimize" section with the scene's pressure regions and poses resolved
  /// (parse_optimization_scene); parsed at the first call. InputError when the section is
  /// missing or invalid.
  const OptimizationSpec& optimization();

  /// Builds the body, its limit surface, the garment and the simulation (load_scene,
  /// make_simulation); a no-op once loaded. The body import's warnings go to stderr.
  void load();
  bool loaded() const { return loaded_ != nullptr; }
  /// The loaded scene (loads it first).
  LoadedScene& loaded_scene();
  /// The simulation of the garment on the body (loads the scene first). It starts at the
  /// initial garment; simulate() and optimize() move it to their equilibria.
  GarmentSimulation& simulation();

  /// Sets the Newton progress callback of the forward solves (empty: none); returns the
  /// previous one.
  NewtonStepCallback set_newton_progress(NewtonStepCallback callback);

  /// When the scene was read: the start of the run's wall time.
  std::chrono::steady_clock::time_point read_time() const { return read_time_; }

  /// The inputs of the run so far (scene/checkpoint_inputs.hpp's run_inputs_json): the
  /// scene document and every file read since the scene began to be read (the body
  /// mesh, the layout, the shape target, ... once loaded), by content hash. A checkpoint
  /// records them; a resumed run is refused when they differ.
  nlohmann::json inputs_json() const;

 private:
  Scene(SceneSpec spec, std::chrono::steady_clock::time_point read_time,
        std::uint64_t first_input_read, nlohmann::json document);

  SceneSpec spec_;  // until loaded; then loaded_->spec
  std::optional<OptimizationSpec> optimization_;
  std::unique_ptr<LoadedScene> loaded_;
  std::unique_ptr<GarmentSimulation> simulation_;
  /// The callback the simulation's Newton options forward to (shared: the simulation
  /// keeps a copy of the forwarding function).
  std::shared_ptr<NewtonStepCallback> newton_progress_;
  std::chrono::steady_clock::time_point read_time_;
  /// input_reads() before the scene was read (common/input_file.hpp).
  std::uint64_t first_input_read_ = 0;
  /// The document of a scene made from_json (null for a scene file, read again).
  nlohmann::json document_;
};

}  // namespace tightfit::api
