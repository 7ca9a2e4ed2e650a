#include "tightfit/api/scene.hpp"

#include <utility>

#include "tightfit/common/input_file.hpp"
#include "tightfit/scene/checkpoint_inputs.hpp"

namespace tightfit::api {

Scene::Scene(SceneSpec spec, std::chrono::steady_clock::time_point read_time,
             std::uint64_t first_input_read, nlohmann::json document)
    : spec_(std::move(spec)),
      newton_progress_(std::make_shared<NewtonStepCallback>()),
      read_time_(read_time),
      first_input_read_(first_input_read),
      document_(std::move(document)) {}

Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene Scene::read(const std::filesystem::path& file) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t reads = input_reads();
  return Scene(read_scene(file), start, reads, nullptr);
}

Scene Scene::from_json(const nlohmann::json& document, const std::string& name,
                       const std::filesystem::path& base_dir) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t reads = input_reads();
  return Scene(parse_scene(document, name, base_dir), start, reads, document);
}

const SceneSpec& Scene::spec() const { return loaded_ ? loaded_->spec : spec_; }

const OptimizationSpec& Scene::optimization() {
  if (!optimization_) optimization_ = scene_optimization(spec());
  return *optimization_;
}

void Scene::load() {
  if (loaded_) return;
  // The simulation copies the Newton options: they forward to the callback slot, which
  // set_newton_progress changes at any time.
  spec_.newton.on_step = [progress = newton_progress_](const NewtonIteration& step,
                                                       double seconds) {
    if (*progress) (*progress)(step, seconds);
  };
  loaded_ = load_scene(spec_);  // a copy: spec_ stays whole when loading fails
  simulation_ = make_simulation(*loaded_);
}

LoadedScene& Scene::loaded_scene() {
  load();
  return *loaded_;
}

GarmentSimulation& Scene::simulation() {
  load();
  return *simulation_;
}

nlohmann::json Scene::inputs_json() const {
  if (document_.is_null()) return run_inputs_json(first_input_read_, file());
  return run_inputs_json(first_input_read_, document_, file());
}

NewtonStepCallback Scene::set_newton_progress(NewtonStepCallback callback) {
  return std::exchange(*newton_progress_, std::move(callback));
}

}  // namespace tightfit::api
