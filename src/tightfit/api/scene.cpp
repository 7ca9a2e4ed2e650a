#include "tightfit/api/scene.hpp"

#include <utility>

namespace tightfit::api {

Scene::Scene(SceneSpec spec, std::chrono::steady_clock::time_point read_time)
    : spec_(std::move(spec)),
      newton_progress_(std::make_shared<NewtonStepCallback>()),
      read_time_(read_time) {}

Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene Scene::read(const std::filesystem::path& file) {
  const auto start = std::chrono::steady_clock::now();
  return Scene(read_scene(file), start);
}

Scene Scene::from_json(const nlohmann::json& document, const std::string& name,
                       const std::filesystem::path& base_dir) {
  const auto start = std::chrono::steady_clock::now();
  return Scene(parse_scene(document, name, base_dir), start);
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

NewtonStepCallback Scene::set_newton_progress(NewtonStepCallback callback) {
  return std::exchange(*newton_progress_, std::move(callback));
}

}  // namespace tightfit::api
