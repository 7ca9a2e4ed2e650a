#include "optimize_run.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "kept_failure.hpp"
#include "optimize_progress.hpp"
#include "run_outputs.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/interrupt.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/optimization_checkpoint.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/optimization_setup.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

/// The stage of a run before its first iteration is reported (the initial equilibrium).
constexpr const char* kStartOfRun = "the start of the run";

/// The checkpoint a failed run can be resumed from (empty file: none yet).
struct LastCheckpoint {
  fs::path file;
  int iteration = 0;
  bool resumed = false;  ///< the checkpoint this run resumed from (none written since)
};

/// "optimize failed during STAGE: WHAT; last good checkpoint: FILE (iteration N); continue
/// with tightfit optimize SCENE --out DIR --resume FOLDER" (or that there is none).
std::string failure_message(const std::string& stage, const std::string& what,
                            const LastCheckpoint& last, const std::string& scene_file) {
  std::string text = "optimize failed during " + stage + ": " + what + "; ";
  if (last.file.empty()) return text + "no checkpoint was written (start again from the scene)";
  const fs::path folder = last.file.has_parent_path() ? last.file.parent_path() : fs::path(".");
  return text + (last.resumed ? "last checkpoint: " : "last good checkpoint: ") +
         last.file.string() + " (iteration " + std::to_string(last.iteration) +
         (last.resumed ? ", the one this run resumed from" : "") +
         "); continue with tightfit optimize " + scene_file + " --out DIR --resume " +
         folder.string();
}

}  // namespace

void run_optimize(const OptimizeRequest& request) {
  const std::string& scene_file = request.scene_file;
  const std::string& out_dir = request.out_dir;
  const std::string& resume_dir = request.resume_dir;
  const int max_iterations = request.max_iterations;
  const bool force = request.force;
  const std::string& keep_failed = request.keep_failed;
  const auto t_start = SteadyClock::now();
  OptimizationScene input = read_optimization_scene(scene_file);
  check_keep_failed_folder(keep_failed, out_dir);
  if (max_iterations >= 0) input.optimization.optimizer.max_iterations = max_iterations;
  const OptimizationSpec& spec = input.optimization;
  const fs::path out(out_dir);
  prepare_output_folder(out, force);
  mark_output_folder(out, "optimize");

  auto scene = load_scene(input.scene);
  auto sim = make_simulation(*scene);
  const auto objective = build_objective(spec, *sim);
  const std::vector<std::string> names = term_names(*objective);
  std::printf("tightfit optimize: %d garment vertices, %d triangles, %zu pieces; terms:",
              sim->garment().num_garment_vertices(),
              static_cast<int>(sim->garment().topology->garment_triangles.rows()),
              sim->garment().pattern.pieces.size());
  for (size_t k = 0; k < names.size(); ++k)
    std::printf(" %s (w %g)", names[k].c_str(), objective->entries()[k].weight);
  std::printf("\n");

  DesignProblem problem(*sim, objective, spec.problem,
                        [&spec](const GarmentSimulation& s) { return build_objective(spec, s); });
  PatternOptimizer optimizer(problem, spec.optimizer);
  if (!resume_dir.empty()) {
    const fs::path file = fs::path(resume_dir) / "checkpoint.json";
    try {
      optimizer.resume(read_checkpoint(file, names));
    } catch (const InputError& e) {
      if (e.source() == file.string()) throw;
      // e.g. a checkpoint of another garment (source "checkpoint"): name the file instead
      std::string what = e.what();
      if (what.starts_with(e.source() + ": ")) what.erase(0, e.source().size() + 2);
      throw InputError(file.string(), what);
    }
    std::printf("  resuming from %s at iteration %d\n", file.c_str(),
                optimizer.checkpoint().iteration);
  } else {
    std::printf("  initial equilibrium...\n");
    std::fflush(stdout);
  }
  std::printf("  %d design parameters (boundary points of %zu pieces)\n", problem.num_parameters(),
              sim->garment().pattern.pieces.size());

  const fs::path checkpoint_file = out / "checkpoint.json";
  // A solver failure from here on (a non-finite state, a NaN refused by a writer, see
  // common/finite_output.hpp) names the stage it happened in and the last good
  // checkpoint, the one a --resume continues from.
  std::string stage = kStartOfRun;
  LastCheckpoint last;
  if (!resume_dir.empty())
    last = {fs::path(resume_dir) / "checkpoint.json", optimizer.checkpoint().iteration, true};
  try {
    // Ctrl-C / SIGTERM: the current iteration finishes, then the run stops and writes the
    // checkpoint and the outputs of the last accepted pattern as after a normal stop.
    const InterruptGuard interrupts;
    std::optional<TriMesh> initial_garment;  // the initial equilibrium (unknown on resume)
    OptimizeProgress progress(names, spec.optimizer.max_iterations, request.terse);
    const OptimizationResult result = optimizer.run(
        [&](const OptimizationIteration& it) {
          if (it.iteration == 0 && resume_dir.empty())
            initial_garment =
                TriMesh{sim->garment_positions(), sim->garment().topology->garment_triangles};
          progress.print(it);
          stage = "writing history.json and checkpoint.json after iteration " +
                  std::to_string(it.iteration);
          write_json_atomically(out / "history.json", history_json(optimizer.history(), names), 2);
          if (it.iteration % spec.checkpoint_every == 0) {
            write_checkpoint(checkpoint_file, optimizer.checkpoint(), names);
            last = {checkpoint_file, it.iteration, false};
          }
          stage = "iteration " + std::to_string(it.iteration + 1);
        },
        [] { return interrupt_requested(); });
    stage = "writing the final checkpoint";
    write_checkpoint(checkpoint_file, optimizer.checkpoint(), names);
    last = {checkpoint_file, optimizer.checkpoint().iteration, false};
    stage = "writing the outputs of iteration " + std::to_string(result.iterations);
    std::printf("  stopped: %s\n", result.stop_reason.c_str());

    // The simulation holds the accepted pattern and its equilibrium. The report comes
    // last: it needs the viewer's npm packages, and its failure must not cost the rest.
    const auto t0 = SteadyClock::now();
    const FitAnalysis fit = sim->analyze();
    const auto op = input.scene.pressure_operator;
    const std::vector<OptimizationIteration>& history = optimizer.history();
    RunState state = make_run_state("optimize", input.scene, sim->garment(), sim->problem().state(),
                                    &scene->garment.pattern);
    state.term_names = names;
    state.history = history;
    state.initial_garment = initial_garment;
    nlohmann::json initial_terms, final_terms;
    for (size_t k = 0; k < names.size(); ++k) {
      initial_terms[names[k]] = history.front().term_values[k];
      final_terms[names[k]] = history.back().term_values[k];
    }
    nlohmann::json& result_json = state.result;
    result_json["run"] = run_identity_json("optimize");
    result_json["scene"] = scene_file;
    result_json["optimization"] = {
        {"converged", result.converged},
        {"interrupted", result.interrupted},
        {"stop_reason", result.stop_reason},
        {"iterations", result.iterations},
        {"objective_initial", history.front().value},
        {"objective_final", history.back().value},
        {"terms_initial", initial_terms},
        {"terms_final", final_terms},
        {"gradient_norm_initial", history.front().gradient_norm},
        {"gradient_norm_final", history.back().gradient_norm},
        {"design_parameters", problem.num_parameters()},
        {"force_residual_n", sim->problem().force_norm(sim->problem().gradient())},
        {"seconds_optimization", history.back().seconds}};
    result_json["compute"] = compute_json();
    result_json["counts"] = {
        {"body_vertices", scene->body.num_vertices()},
        {"body_tets", scene->body.volume.num_tets()},
        {"garment_vertices", sim->garment().num_garment_vertices()},
        {"garment_triangles", sim->garment().topology->garment_triangles.rows()},
        {"pattern_pieces", sim->garment().pattern.pieces.size()},
        {"dofs", sim->problem().num_dofs()}};
    nlohmann::json seconds;
    for (const auto& [name, s] : scene->stage_seconds) seconds[name] = s;
    seconds["optimization_this_run"] = result.seconds;
    seconds["analysis"] = seconds_since(t0);
    seconds["total_this_run"] = seconds_since(t_start);
    result_json["seconds"] = seconds;
    std::printf("  objective %.6e -> %.6e in %d iterations (%.1f s)\n", history.front().value,
                history.back().value, result.iterations, history.back().seconds);
    std::vector<std::string> files =
        write_fit_run_outputs(out, *sim, fit, op, state, &scene->garment.pattern);
    files.push_back("checkpoint.json");
    for (const auto& f : files) std::printf("  %s\n", (out / f).c_str());
    if (result.interrupted) {
      const int signal = interrupt_signal();
      std::printf(
          "  interrupted by %s: the files above hold the pattern of iteration %d; "
          "continue with\n    tightfit optimize %s --out DIR --resume %s\n",
          signal_name(signal), result.iterations, scene_file.c_str(), out.c_str());
      std::fflush(stdout);
      throw Interrupted{signal};
    }
  } catch (const SolverError& e) {
    // The initial equilibrium is the one forward solve whose failure ends a run (later
    // trials back off): keep its last state where the user asked.
    if (!keep_failed.empty() && stage == kStartOfRun) {
      try {
        report_kept_failure(keep_failed, force, scene_file, *scene, *sim, e.what());
      } catch (const std::exception& kept) {
        std::printf("  the failed state could not be kept: %s\n", kept.what());
      }
    }
    throw SolverError(failure_message(stage, e.what(), last, scene_file));
  }
}

}  // namespace tightfit::app
