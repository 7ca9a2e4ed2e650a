#include "optimize_run.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "kept_failure.hpp"
#include "optimize_progress.hpp"
#include "resume_check.hpp"
#include "run_outputs.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/input_file.hpp"
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

/// `word` quoted for a POSIX shell when it holds anything but safe characters.
std::string shell_word(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_-+=.,/:@%") == std::string::npos;
  if (safe) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The command that continues a run from the checkpoint in `folder`, with the options
/// of this one that change its result.
std::string resume_command(const OptimizeRequest& request, const fs::path& folder) {
  std::string command = "tightfit optimize " + shell_word(request.scene_file) + " --out " +
                        shell_word(request.out_dir) + " --resume " + shell_word(folder.string());
  if (request.max_iterations >= 0)
    command += " --max-iterations " + std::to_string(request.max_iterations);
  if (request.time_limit >= 0.0) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.17g", request.time_limit);
    command += std::string(" --time-limit ") + seconds;
  }
  if (request.terse) command += " --terse";
  return command;
}

/// "optimize failed during STAGE: WHAT; last good checkpoint: FILE (iteration N); continue
/// with tightfit optimize SCENE --out OUT --resume FOLDER ..." (or that there is none).
std::string failure_message(const std::string& stage, const std::string& what,
                            const LastCheckpoint& last, const OptimizeRequest& request) {
  std::string text = "optimize failed during " + stage + ": " + what + "; ";
  if (last.file.empty()) return text + "no checkpoint was written (start again from the scene)";
  const fs::path folder = last.file.has_parent_path() ? last.file.parent_path() : fs::path(".");
  return text + (last.resumed ? "last checkpoint: " : "last good checkpoint: ") +
         last.file.string() + " (iteration " + std::to_string(last.iteration) +
         (last.resumed ? ", the one this run resumed from" : "") + "); continue with " +
         resume_command(request, folder);
}

/// history.json with the best iteration marked (run_outputs.hpp's mark_best_iteration).
nlohmann::json marked_history_json(const std::vector<OptimizationIteration>& history,
                                   const std::vector<std::string>& names, int best_iteration) {
  nlohmann::json j = history_json(history, names);
  mark_best_iteration(j, best_iteration);
  return j;
}

/// The iteration of the lowest objective in `history` (after remeshings too): the best
/// design so far while the run goes on.
int best_iteration_so_far(const std::vector<OptimizationIteration>& history) {
  int best = 0;
  double value = std::numeric_limits<double>::infinity();
  for (const OptimizationIteration& it : history)
    for (double v :
         {it.value, it.remesh && it.remesh->failure.empty() ? it.remesh->value : it.value})
      if (v < value) {
        value = v;
        best = it.iteration;
      }
  return best;
}

/// The scene, simulation and objective of a run, loaded and announced.
struct OptimizeSetup {
  OptimizationScene input;
  std::unique_ptr<LoadedScene> scene;
  std::unique_ptr<GarmentSimulation> sim;
  std::shared_ptr<const DesignTermSum> objective;
  std::vector<std::string> names;
  /// The output folder, locked for the run (common/output_directory.hpp).
  std::unique_ptr<OutputDirectory> folder;
  /// The inputs the run read (resume_check.hpp), recorded in every checkpoint.
  nlohmann::json inputs;
};

OptimizeSetup load_optimize_setup(const OptimizeRequest& request) {
  OptimizeSetup s;
  const std::uint64_t reads_before = input_reads();  // the inputs of this run follow
  s.input = read_optimization_scene(request.scene_file);
  check_keep_failed_folder(request.keep_failed, request.out_dir);
  PatternOptimizerOptions& o = s.input.optimization.optimizer;
  if (request.max_iterations >= 0) o.max_iterations = request.max_iterations;
  if (request.time_limit >= 0.0) o.time_limit = request.time_limit;
  s.folder = std::make_unique<OutputDirectory>(request.out_dir, request.force, "optimize");
  s.scene = load_scene(s.input.scene);
  s.sim = make_simulation(*s.scene);
  s.objective = build_objective(s.input.optimization, *s.sim);
  s.names = term_names(*s.objective);
  s.inputs = run_inputs_json(reads_before, request.scene_file);
  std::printf("tightfit optimize: %d garment vertices, %d triangles, %zu pieces; terms:",
              s.sim->garment().num_garment_vertices(),
              static_cast<int>(s.sim->garment().topology->garment_triangles.rows()),
              s.sim->garment().pattern.pieces.size());
  for (size_t k = 0; k < s.names.size(); ++k)
    std::printf(" %s (w %g)", s.names[k].c_str(), s.objective->entries()[k].weight);
  std::printf("\n");
  return s;
}

/// Resumes `optimizer` from RESUME/checkpoint.json of a run of the same `inputs` (errors
/// name that file).
void resume_from(PatternOptimizer& optimizer, const std::string& resume_dir,
                 const std::vector<std::string>& names, const nlohmann::json& inputs) {
  const fs::path file = fs::path(resume_dir) / "checkpoint.json";
  try {
    optimizer.resume(read_checkpoint_for(file, names, &inputs));
  } catch (const InputError& e) {
    if (e.source() == file.string()) throw;
    // e.g. a checkpoint of another garment (source "checkpoint"): name the file instead
    std::string what = e.what();
    if (what.starts_with(e.source() + ": ")) what.erase(0, e.source().size() + 2);
    throw InputError(file.string(), what);
  }
  std::printf("  resuming from %s at iteration %d\n", file.c_str(),
              optimizer.checkpoint().iteration);
}

/// result.json's "optimization" section: the stop rule in words and by name, and the
/// objective of the returned (best) design.
nlohmann::json optimization_json(const OptimizationResult& result,
                                 const std::vector<OptimizationIteration>& history,
                                 const std::vector<std::string>& names, int design_parameters,
                                 double force_residual) {
  nlohmann::json initial_terms, final_terms;
  for (size_t k = 0; k < names.size(); ++k) {
    initial_terms[names[k]] = history.front().term_values[k];
    if (k < result.final_terms.size()) final_terms[names[k]] = result.final_terms[k];
  }
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
                      {"design_parameters", design_parameters},
                      {"force_residual_n", force_residual},
                      {"seconds_optimization", history.back().seconds}};
  if (!result.gradient_check.empty()) {
    nlohmann::json checks = nlohmann::json::array();
    for (const DirectionalCheck& c : result.gradient_check)
      checks.push_back({{"adjoint", c.adjoint},
                        {"finite_difference", c.finite_difference},
                        {"relative_error", c.relative_error}});
    j["gradient_check"] = checks;
  }
  return j;
}

/// The outputs of the returned design (the simulation holds it): result.json, the fit,
/// the pattern and the report. Returns the files written.
std::vector<std::string> write_optimize_outputs(const fs::path& out, const OptimizeRequest& request,
                                                OptimizeSetup& s, const PatternOptimizer& optimizer,
                                                const OptimizationResult& result,
                                                const std::optional<TriMesh>& initial_garment,
                                                int design_parameters,
                                                SteadyClock::time_point t_start) {
  const auto t0 = SteadyClock::now();
  GarmentSimulation& sim = *s.sim;
  const FitAnalysis fit = sim.analyze();
  const std::vector<OptimizationIteration>& history = optimizer.history();
  RunState state = make_run_state("optimize", s.input.scene, sim.garment(), sim.problem().state(),
                                  &s.scene->garment.pattern);
  state.term_names = s.names;
  state.history = history;
  state.initial_garment = initial_garment;
  nlohmann::json& result_json = state.result;
  result_json["run"] = run_identity_json("optimize");
  result_json["scene"] = request.scene_file;
  result_json["optimization"] =
      optimization_json(result, history, s.names, design_parameters,
                        sim.problem().force_norm(sim.problem().gradient()));
  result_json["compute"] = compute_json();
  result_json["counts"] = {{"body_vertices", s.scene->body.num_vertices()},
                           {"body_tets", s.scene->body.volume.num_tets()},
                           {"garment_vertices", sim.garment().num_garment_vertices()},
                           {"garment_triangles", sim.garment().topology->garment_triangles.rows()},
                           {"pattern_pieces", sim.garment().pattern.pieces.size()},
                           {"dofs", sim.problem().num_dofs()}};
  nlohmann::json seconds;
  for (const auto& [name, value] : s.scene->stage_seconds) seconds[name] = value;
  seconds["optimization_this_run"] = result.seconds;
  seconds["analysis"] = seconds_since(t0);
  seconds["total_this_run"] = seconds_since(t_start);
  result_json["seconds"] = seconds;
  std::vector<std::string> files = write_fit_run_outputs(
      out, sim, fit, s.input.scene.pressure_operator, state, &s.scene->garment.pattern);
  files.push_back("checkpoint.json");
  return files;
}

/// The closing lines: the objective of the returned design, the files, and last the
/// rule that ended the run, in words.
void print_summary(const OptimizationResult& result, const std::vector<OptimizationIteration>& h,
                   const fs::path& out, const std::vector<std::string>& files) {
  std::printf("  objective %.6e -> %.6e (iteration %d%s) in %d iterations (%.1f s)\n",
              h.front().value, result.final_value, result.best_iteration,
              result.best_after_remesh ? ", after its remeshing" : "", result.iterations,
              h.back().seconds);
  if (result.best_restored)
    std::printf(
        "  the last iteration ended at %.6e, above the best design: the outputs hold the best "
        "one (iteration %d); checkpoint.json holds the last one\n",
        result.last_value, result.best_iteration);
  for (const auto& f : files) std::printf("  %s\n", (out / f).c_str());
  std::printf("  stopped (%s): %s\n", stop_rule_name(result.rule), result.stop_reason.c_str());
}

}  // namespace

void run_optimize(const OptimizeRequest& request) {
  const auto t_start = SteadyClock::now();
  OptimizeSetup s = load_optimize_setup(request);
  const OptimizationSpec& spec = s.input.optimization;
  const fs::path out(request.out_dir);
  DesignProblem problem(*s.sim, s.objective, spec.problem,
                        [&spec](const GarmentSimulation& g) { return build_objective(spec, g); });
  PatternOptimizer optimizer(problem, spec.optimizer);
  const bool resuming = !request.resume_dir.empty();
  if (resuming) {
    resume_from(optimizer, request.resume_dir, s.names, s.inputs);
  } else {
    std::printf("  initial equilibrium...\n");
    std::fflush(stdout);
  }
  std::printf("  %d design parameters (boundary points of %zu pieces)\n", problem.num_parameters(),
              s.sim->garment().pattern.pieces.size());

  const fs::path checkpoint_file = out / "checkpoint.json";
  OutputDirectory& folder = *s.folder;
  const auto publish_history = [&](int best) {
    folder.publish("history.json", [&](const fs::path& file) {
      write_json_atomically(file, marked_history_json(optimizer.history(), s.names, best), 2);
    });
  };
  const auto publish_checkpoint = [&] {
    folder.publish("checkpoint.json", [&](const fs::path& file) {
      write_checkpoint_with_inputs(file, optimizer.checkpoint(), s.names, s.inputs);
    });
  };
  // A solver failure from here on (a non-finite state, a NaN refused by a writer, see
  // common/finite_output.hpp) names the stage it happened in and the last good
  // checkpoint, the one a --resume continues from.
  std::string stage = kStartOfRun;
  LastCheckpoint last;
  if (resuming)
    last = {fs::path(request.resume_dir) / "checkpoint.json", optimizer.checkpoint().iteration,
            true};
  try {
    // Ctrl-C / SIGTERM: the current iteration finishes, then the run stops and writes the
    // checkpoint and the outputs of the returned pattern as after a normal stop.
    const InterruptGuard interrupts;
    std::optional<TriMesh> initial_garment;  // the initial equilibrium (unknown on resume)
    OptimizeProgress progress(s.names, spec.optimizer.max_iterations, request.terse);
    const OptimizationResult result = optimizer.run(
        [&](const OptimizationIteration& it) {
          if (it.iteration == 0 && !resuming)
            initial_garment =
                TriMesh{s.sim->garment_positions(), s.sim->garment().topology->garment_triangles};
          progress.print(it);
          stage = "writing history.json and checkpoint.json after iteration " +
                  std::to_string(it.iteration);
          publish_history(best_iteration_so_far(optimizer.history()));
          if (it.iteration % spec.checkpoint_every == 0) {
            publish_checkpoint();
            last = {checkpoint_file, it.iteration, false};
          }
          stage = "iteration " + std::to_string(it.iteration + 1);
        },
        [] { return interrupt_requested(); });
    stage = "writing the final checkpoint";
    publish_checkpoint();
    publish_history(result.best_iteration);
    last = {checkpoint_file, optimizer.checkpoint().iteration, false};
    stage = "writing the outputs of iteration " + std::to_string(result.best_iteration);
    // The report comes last in write_fit_run_outputs: it needs the viewer's npm packages,
    // and its failure must not cost the rest.
    const std::vector<std::string> files =
        write_optimize_outputs(folder.staging(), request, s, optimizer, result, initial_garment,
                               problem.num_parameters(), t_start);
    folder.commit();  // all at once (common/output_directory.hpp)
    print_summary(result, optimizer.history(), out, files);
    if (result.interrupted) {
      const int signal = interrupt_signal();
      std::printf(
          "  interrupted by %s: the files above hold the pattern of iteration %d; "
          "continue with\n    %s\n",
          signal_name(signal), result.best_iteration, resume_command(request, out).c_str());
      std::fflush(stdout);
      throw Interrupted{signal};
    }
  } catch (const SolverError& e) {
    // The initial equilibrium is the one forward solve whose failure ends a run (later
    // trials back off): keep its last state where the user asked.
    if (!request.keep_failed.empty() && stage == kStartOfRun) {
      try {
        report_kept_failure(request.keep_failed, request.force, request.scene_file, *s.scene,
                            *s.sim, e.what());
      } catch (const std::exception& kept) {
        std::printf("  the failed state could not be kept: %s\n", kept.what());
      }
    }
    if (!last.file.empty() && !last.resumed) folder.keep_published();  // resumable
    throw SolverError(failure_message(stage, e.what(), last, request));
  }
}

}  // namespace tightfit::app
