#include "tightfit/api/optimize.hpp"

#include <limits>
#include <string>
#include <utility>

#include "tightfit/api/run_outputs.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/checkpoint_inputs.hpp"
#include "tightfit/scene/run_state.hpp"

namespace tightfit::api {

Optimization::Optimization(Scene& scene, const OptimizeOptions& options)
    : scene_(scene), spec_(scene.optimization()) {
  if (options.max_iterations >= 0) spec_.optimizer.max_iterations = options.max_iterations;
  if (options.time_limit >= 0.0) spec_.optimizer.time_limit = options.time_limit;
  GarmentSimulation& sim = scene.simulation();
  // The terms' weights refer to the scene's initial mesh, also after remeshings and on
  // resume (which starts from the scene's garment too).
  spec_.resolution = resolution_of(sim.garment());
  objective_ = build_objective(spec_, sim);
  names_ = tightfit::term_names(*objective_);
  inputs_ = scene.inputs_json();  // the scene and every file its loading read
  problem_ = std::make_unique<DesignProblem>(
      sim, objective_, spec_.problem,
      [spec = spec_](const GarmentSimulation& s) { return build_objective(spec, s); });
  optimizer_ = std::make_unique<PatternOptimizer>(*problem_, spec_.optimizer);
}

Optimization::~Optimization() = default;

void Optimization::resume(const std::filesystem::path& file) {
  try {
    optimizer_->resume(read_checkpoint_for(file, names_, &inputs_));
  } catch (const InputError& e) {
    if (e.source() == file.string()) throw;
    // e.g. a checkpoint of another garment (source "checkpoint"): name the file instead
    std::string what = e.what();
    if (what.starts_with(e.source() + ": ")) what.erase(0, e.source().size() + 2);
    throw InputError(file.string(), what);
  }
  resumed_ = true;
}

void Optimization::write_checkpoint(const std::filesystem::path& file) const {
  write_checkpoint_with_inputs(file, optimizer_->checkpoint(), names_, inputs_);
}

nlohmann::json Optimization::history_json(int best) const {
  nlohmann::json j = tightfit::history_json(history(), names_);
  mark_best_iteration(j, best);
  return j;
}

int Optimization::best_iteration_so_far() const {
  int best = 0;
  double value = std::numeric_limits<double>::infinity();
  for (const OptimizationIteration& it : history())
    for (double v :
         {it.value, it.remesh && it.remesh->failure.empty() ? it.remesh->value : it.value})
      if (v < value) {
        value = v;
        best = it.iteration;
      }
  return best;
}

OptimizationResult Optimization::run(const IterationObserver& on_iteration,
                                     const std::function<bool()>& stop_requested) {
  bool stop = false;
  GarmentSimulation& sim = scene_.simulation();
  return optimizer_->run(
      [&](const OptimizationIteration& it) {
        if (it.iteration == 0 && !resumed_)
          initial_garment_ =
              TriMesh{sim.garment_positions(), sim.garment().topology->garment_triangles};
        if (on_iteration && !on_iteration(it)) stop = true;
      },
      [&] { return stop || (stop_requested && stop_requested()); });
}

namespace {

/// The adjoint-versus-finite-difference checks of a stationary stop, as JSON.
nlohmann::json gradient_check_json(const std::vector<DirectionalCheck>& checks) {
  nlohmann::json j = nlohmann::json::array();
  for (const DirectionalCheck& c : checks)
    j.push_back({{"adjoint", c.adjoint},
                 {"finite_difference", c.finite_difference},
                 {"relative_error", c.relative_error}});
  return j;
}

}  // namespace

nlohmann::json optimization_result_json(Optimization& optimization,
                                        const OptimizationResult& result) {
  const std::vector<OptimizationIteration>& history = optimization.history();
  const std::vector<std::string>& names = optimization.term_names();
  nlohmann::json initial_terms, final_terms;
  for (size_t k = 0; k < names.size(); ++k) {
    initial_terms[names[k]] = history.front().term_values[k];
    if (k < result.final_terms.size()) final_terms[names[k]] = result.final_terms[k];
  }
  GarmentSimulation& sim = optimization.scene().simulation();
  nlohmann::json j = {{"converged", result.converged},
                      {"interrupted", result.interrupted},
                      {"stop_rule", stop_rule_name(result.rule)},
                      {"stop_reason", result.stop_reason},
                      {"iterations", result.iterations},
                      {"best_iteration", result.best_iteration},
                      {"best_after_remesh", result.best_after_remesh},
                      {"best_restored", result.best_restored},
                      {"objective_initial", history.front().value},
                      {"objective_final", result.final_value},
                      {"objective_last_iteration", result.last_value},
                      {"terms_initial", initial_terms},
                      {"terms_final", final_terms},
                      {"gradient_norm_initial", history.front().gradient_norm},
                      {"gradient_norm_final", result.final_gradient_norm},
                      {"design_parameters", optimization.num_parameters()},
                      {"force_residual_n", sim.problem().force_norm(sim.problem().gradient())},
                      {"seconds_optimization", history.back().seconds}};
  if (!result.gradient_check.empty())
    j["gradient_check"] = gradient_check_json(result.gradient_check);
  return j;
}

WrittenOutputs write_optimization_outputs(Optimization& optimization,
                                          const OptimizationResult& result,
                                          const std::filesystem::path& folder) {
  Scene& scene = optimization.scene();
  const LoadedScene& loaded = scene.loaded_scene();
  const GarmentSimulation& sim = scene.simulation();
  const auto t0 = SteadyClock::now();
  const FitAnalysis fit = sim.analyze();
  RunState state = make_run_state("optimize", loaded.spec, sim.garment(), sim.problem().state(),
                                  &loaded.garment.pattern);
  state.term_names = optimization.term_names();
  state.history = optimization.history();
  state.initial_garment = optimization.initial_garment();
  nlohmann::json& result_json = state.result;
  result_json["run"] = run_identity_json("optimize");
  result_json["scene"] = scene.file();
  result_json["optimization"] = optimization_result_json(optimization, result);
  result_json["compute"] = compute_json();
  result_json["counts"] = {{"body_vertices", loaded.body.num_vertices()},
                           {"body_tets", loaded.body.volume.num_tets()},
                           {"garment_vertices", sim.garment().num_garment_vertices()},
                           {"garment_triangles", sim.garment().topology->garment_triangles.rows()},
                           {"pattern_pieces", sim.garment().pattern.pieces.size()},
                           {"dofs", sim.problem().num_dofs()}};
  nlohmann::json seconds;
  for (const auto& [name, s] : loaded.stage_seconds) seconds[name] = s;
  seconds["optimization_this_run"] = result.seconds;
  seconds["analysis"] = seconds_since(t0);
  seconds["total_this_run"] = seconds_since(scene.read_time());
  result_json["seconds"] = seconds;
  optimization.write_checkpoint(folder / "checkpoint.json");
  WrittenOutputs out;
  out.files = write_fit_run_outputs(folder, sim, fit, loaded.spec.pressure_operator, state,
                                    &loaded.garment.pattern);
  out.files.push_back("checkpoint.json");
  out.result = std::move(state.result);
  return out;
}

}  // namespace tightfit::api
