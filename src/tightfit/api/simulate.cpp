#include "tightfit/api/simulate.hpp"

#include <utility>

#include "tightfit/api/run_outputs.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/run_state.hpp"

namespace tightfit::api {
namespace {

double energy_or_zero(const Energy* e, const VecX& x) { return e ? e->value(x) : 0.0; }

/// result.json's "counts" and "energies_j" of a simulation.
void add_simulation_sizes(const LoadedScene& scene, const GarmentSimulation& sim,
                          nlohmann::json& result) {
  const Points3& x = sim.garment_positions();
  const VecX xf = Eigen::Map<const VecX>(x.data(), x.size());
  const Points3& y = sim.body_positions();
  const VecX yf = Eigen::Map<const VecX>(y.data(), y.size());
  result["counts"] = {{"body_vertices", scene.body.num_vertices()},
                      {"body_tets", scene.body.volume.num_tets()},
                      {"body_surface_faces", scene.body.surface.num_faces()},
                      {"body_pinned", scene.body.pinned.size()},
                      {"garment_vertices", sim.garment().num_garment_vertices()},
                      {"garment_triangles", sim.garment().topology->garment_triangles.rows()},
                      {"pattern_pieces", sim.garment().pattern.pieces.size()},
                      {"dofs", sim.problem().num_dofs()}};
  result["energies_j"] = {{"cloth", sim.cloth().value(xf)},
                          {"seams", energy_or_zero(sim.seams(), xf)},
                          {"body", sim.body_energy().value(yf)}};
}

}  // namespace

SimulationRun simulate(Scene& scene, const SimulateOptions& options) {
  GarmentSimulation& sim = scene.simulation();
  // The scene's own progress callback again afterwards, also when the solve throws.
  struct Restore {
    Scene& scene;
    NewtonStepCallback previous;
    ~Restore() { scene.set_newton_progress(std::move(previous)); }
  } restore{scene, scene.set_newton_progress(options.on_newton_step)};
  SimulationRun run;
  auto t0 = SteadyClock::now();
  run.newton = sim.solve();
  run.seconds_solve = seconds_since(t0);
  t0 = SteadyClock::now();
  run.fit = sim.analyze();
  run.seconds_analysis = seconds_since(t0);
  return run;
}

WrittenOutputs write_simulation_outputs(Scene& scene, const SimulationRun& run,
                                        const std::filesystem::path& folder) {
  const LoadedScene& loaded = scene.loaded_scene();
  const GarmentSimulation& sim = scene.simulation();
  RunState state = make_run_state("simulate", loaded.spec, sim.garment(), sim.problem().state());
  nlohmann::json& result = state.result;
  result["run"] = run_identity_json("simulate");
  result["scene"] = scene.file();
  add_simulation_sizes(loaded, sim, result);
  result["newton"] = newton_report_json(run.newton);
  result["compute"] = compute_json();
  nlohmann::json seconds;
  for (const auto& [stage, s] : loaded.stage_seconds) seconds[stage] = s;
  seconds["solve"] = run.seconds_solve;
  seconds["analysis"] = run.seconds_analysis;
  seconds["total"] = seconds_since(scene.read_time());
  result["seconds"] = seconds;
  WrittenOutputs out;
  out.files = write_fit_run_outputs(folder, sim, run.fit, loaded.spec.pressure_operator, state);
  out.result = std::move(state.result);
  return out;
}

}  // namespace tightfit::api
