/// `tightfit simulate SCENE --out DIR [--keep-failed DIR2]`: the static equilibrium of a
/// garment on a body. With --keep-failed, a solve that does not converge leaves its last
/// state in DIR2 (the fit outputs plus per-vertex maps of the unbalanced force), so that
/// the user can see which part of the layout is at fault; DIR stays untouched.
#include <cstdio>
#include <string>

#include "command_registry.hpp"
#include "fit_summary.hpp"
#include "kept_failure.hpp"
#include "tightfit/api/simulate.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/output_directory.hpp"

namespace tightfit::app {
namespace {

void run_simulate(const std::string& scene_file, const std::string& out_dir,
                  const std::string& keep_failed, bool force) {
  // Bad input fails before the folder is touched.
  api::Scene scene = api::Scene::read(scene_file);
  check_keep_failed_folder(keep_failed, out_dir);
  OutputDirectory out(out_dir, force, "simulate");
  const LoadedScene& loaded = scene.loaded_scene();
  GarmentSimulation& sim = scene.simulation();
  std::printf("tightfit simulate: %d body vertices (%d tets), %d garment vertices, %d triangles\n",
              loaded.body.num_vertices(), loaded.body.volume.num_tets(),
              sim.garment().num_garment_vertices(),
              static_cast<int>(sim.garment().topology->garment_triangles.rows()));
  // Newton's progress, one line per step: a full-body solve takes minutes.
  api::SimulateOptions options;
  options.on_newton_step = [step = 0](const NewtonIteration& it, double seconds) mutable {
    std::printf("  newton %3d  force before %.3e N  energy %.6e J  step %.3g%s%s%s  %.1f s\n",
                ++step, it.force_norm, it.energy, it.step_size, it.chord ? "  (chord)" : "",
                it.regularization > 0.0 ? "  (shifted)" : "", it.body_held ? "  (body held)" : "",
                seconds);
    std::fflush(stdout);
  };
  api::SimulationRun run;
  try {
    run = api::simulate(scene, options);
  } catch (const SolverError& e) {
    if (!keep_failed.empty())
      report_kept_failure(keep_failed, force, scene_file, loaded, sim, e.what());
    throw;
  }
  const NewtonReport& report = run.newton;
  std::printf(
      "  Newton converged in %d iterations (%d of them on the garment with the body held, %d "
      "chord steps, %d factorizations), force residual %.3e N (tolerance %.3e N), %.2f s\n",
      report.iterations, report.garment_first_iterations, report.chord_steps, report.factorizations,
      report.final_force_norm, report.tolerance, run.seconds_solve);
  const api::WrittenOutputs written = api::write_simulation_outputs(scene, run, out.staging());
  out.commit();
  for (const auto& f : written.files) std::printf("  %s/%s\n", out.target().c_str(), f.c_str());
  print_fit_summary(written.result, out.target() / "report.html");
}

/// `tightfit simulate SCENE --out DIR [--force] [--keep-failed DIR2]`.
struct SimulateCommandOptions : SceneRunOptions {
  std::string keep_failed;
};

const CommandRegistration kSimulate{
    "simulate", [](CLI::App& root) {
      auto [cmd, o] = add_command<SimulateCommandOptions>(
          root,
          {"simulate",
           "Static equilibrium of a garment on a body (Newton on the coupled cloth-body system). "
           "Writes garment.ply and body.ply (per-face stretch, regime, pressure; per-vertex "
           "force) and result.json (energies, residual, iterations, time split, pressure "
           "statistics), report.html, fit.glb, the pattern files, and state.json (the run state "
           "for `tightfit export`).",
           "Example:\n  tightfit simulate examples/sleeve_two_panels.json --out out/sleeve"},
          [](const SimulateCommandOptions& options) {
            run_simulate(options.scene, options.out, options.keep_failed, options.force);
          });
      add_scene_run_options(cmd, o);
      cmd.add_option("--keep-failed", o.keep_failed,
                     "When the solve does not converge, write its last state to this folder: the "
                     "fit outputs and garment_residual.ply / body_residual.ply (unbalanced force "
                     "per vertex, N); --out stays untouched");
    }};

}  // namespace
}  // namespace tightfit::app
