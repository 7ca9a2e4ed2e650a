/// `tightfit simulate SCENE --out DIR [--keep-failed DIR2]`: the static equilibrium of a
/// garment on a body. With --keep-failed, a solve that does not converge leaves its last
/// state in DIR2 (the fit outputs plus per-vertex maps of the unbalanced force), so that
/// the user can see which part of the layout is at fault; DIR stays untouched.
#include <cstdio>
#include <filesystem>

#include "command_registry.hpp"
#include "kept_failure.hpp"
#include "run_outputs.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/loader.hpp"

namespace tightfit::app {
namespace {

double energy_of(const Energy* e, const VecX& x) { return e ? e->value(x) : 0.0; }

void run_simulate(const std::string& scene_file, const std::string& out_dir,
                  const std::string& keep_failed, bool force) {
  const auto t_start = SteadyClock::now();
  SceneSpec spec = read_scene(scene_file);  // bad input fails before the folder is touched
  check_keep_failed_folder(keep_failed, out_dir);
  OutputDirectory out(out_dir, force, "simulate");
  auto scene = load_scene(std::move(spec));
  // Newton's progress, one line per step: a full-body solve takes minutes.
  scene->spec.newton.on_step = [step = 0](const NewtonIteration& it, double seconds) mutable {
    std::printf("  newton %3d  force before %.3e N  energy %.6e J  step %.3g%s%s%s  %.1f s\n",
                ++step, it.force_norm, it.energy, it.step_size, it.chord ? "  (chord)" : "",
                it.regularization > 0.0 ? "  (shifted)" : "", it.body_held ? "  (body held)" : "",
                seconds);
    std::fflush(stdout);
  };
  auto sim = make_simulation(*scene);
  std::printf("tightfit simulate: %d body vertices (%d tets), %d garment vertices, %d triangles\n",
              scene->body.num_vertices(), scene->body.volume.num_tets(),
              sim->garment().num_garment_vertices(),
              static_cast<int>(sim->garment().topology->garment_triangles.rows()));
  auto t0 = SteadyClock::now();
  NewtonReport report;
  try {
    report = sim->solve();
  } catch (const SolverError& e) {
    if (!keep_failed.empty())
      report_kept_failure(keep_failed, force, scene_file, *scene, *sim, e.what());
    throw;
  }
  const double t_solve = seconds_since(t0);
  std::printf(
      "  Newton converged in %d iterations (%d of them on the garment with the body held, %d "
      "chord steps, %d factorizations), force residual %.3e N (tolerance %.3e N), %.2f s\n",
      report.iterations, report.garment_first_iterations, report.chord_steps, report.factorizations,
      report.final_force_norm, report.tolerance, t_solve);
  t0 = SteadyClock::now();
  const FitAnalysis fit = sim->analyze();
  const double t_analysis = seconds_since(t0);

  const auto op = scene->spec.pressure_operator;
  const Points3& x = sim->garment_positions();
  const VecX xf = Eigen::Map<const VecX>(x.data(), x.size());
  const Points3& y = sim->body_positions();
  const VecX yf = Eigen::Map<const VecX>(y.data(), y.size());
  RunState state = make_run_state("simulate", scene->spec, sim->garment(), sim->problem().state());
  nlohmann::json& result = state.result;
  result["run"] = run_identity_json("simulate");
  result["scene"] = scene_file;
  result["counts"] = {{"body_vertices", scene->body.num_vertices()},
                      {"body_tets", scene->body.volume.num_tets()},
                      {"body_surface_faces", scene->body.surface.num_faces()},
                      {"body_pinned", scene->body.pinned.size()},
                      {"garment_vertices", sim->garment().num_garment_vertices()},
                      {"garment_triangles", sim->garment().topology->garment_triangles.rows()},
                      {"pattern_pieces", sim->garment().pattern.pieces.size()},
                      {"dofs", sim->problem().num_dofs()}};
  result["energies_j"] = {{"cloth", sim->cloth().value(xf)},
                          {"seams", energy_of(sim->seams(), xf)},
                          {"body", sim->body_energy().value(yf)}};
  result["newton"] = newton_report_json(report);
  result["compute"] = compute_json();
  nlohmann::json seconds;
  for (const auto& [stage, s] : scene->stage_seconds) seconds[stage] = s;
  seconds["solve"] = t_solve;
  seconds["analysis"] = t_analysis;
  seconds["total"] = seconds_since(t_start);
  result["seconds"] = seconds;
  const auto files = write_fit_run_outputs(out.staging(), *sim, fit, op, state);
  out.commit();
  const auto& pr = result["fit"]["pressure_mmhg"];
  std::printf("  pressure %.1f / %.1f / %.1f mmHg (min / median / max)\n", pr["min"].get<double>(),
              pr["median"].get<double>(), pr["max"].get<double>());
  for (const auto& f : files) std::printf("  %s/%s\n", out.target().c_str(), f.c_str());
}

const CommandRegistration kSimulate{
    "simulate", [](CLI::App& root) {
      auto* cmd = root.add_subcommand(
          "simulate",
          "Static equilibrium of a garment on a body (Newton on the coupled cloth-body system). "
          "Writes garment.ply and body.ply (per-face stretch, regime, pressure; per-vertex force) "
          "and result.json (energies, residual, iterations, time split, pressure statistics), "
          "report.html, fit.glb, the pattern files, and state.json (the run state for "
          "`tightfit export`).");
      cmd->footer("Example:\n  tightfit simulate examples/sleeve_two_panels.json --out out/sleeve");
      auto scene = std::make_shared<std::string>();
      auto out = std::make_shared<std::string>();
      auto force = std::make_shared<bool>(false);
      cmd->add_option("scene", *scene, "Scene file (JSON; schema: schema/scene.schema.json)")
          ->required();
      cmd->add_option("--out", *out, kOutHelp)->required();
      auto keep_failed = std::make_shared<std::string>();
      cmd->add_option("--keep-failed", *keep_failed,
                      "When the solve does not converge, write its last state to this folder: the "
                      "fit outputs and garment_residual.ply / body_residual.ply (unbalanced force "
                      "per vertex, N); --out stays untouched");
      cmd->add_flag("--force", *force, kForceHelp);
      cmd->callback(
          [scene, out, keep_failed, force] { run_simulate(*scene, *out, *keep_failed, *force); });
    }};

}  // namespace
}  // namespace tightfit::app
