#include "optimize_run.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "fit_summary.hpp"
#include "kept_failure.hpp"
#include "optimize_progress.hpp"
#include "tightfit/api/optimize.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/interrupt.hpp"
#include "tightfit/common/output_directory.hpp"

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

/// Reads the scene and its "optimize" section (bad input fails before the folder is
/// touched), locks the output folder, loads the scene and builds the optimization.
struct OptimizeSetup {
  std::unique_ptr<api::Scene> scene;
  /// The output folder, locked for the run (common/output_directory.hpp).
  std::unique_ptr<OutputDirectory> folder;
  std::unique_ptr<api::Optimization> optimization;
};

OptimizeSetup load_optimize_setup(const OptimizeRequest& request) {
  OptimizeSetup s;
  s.scene = std::make_unique<api::Scene>(api::Scene::read(request.scene_file));
  s.scene->optimization();
  check_keep_failed_folder(request.keep_failed, request.out_dir);
  s.folder = std::make_unique<OutputDirectory>(request.out_dir, request.force, "optimize");
  s.optimization = std::make_unique<api::Optimization>(
      *s.scene, api::OptimizeOptions{request.max_iterations, request.time_limit});
  const GarmentSimulation& sim = s.scene->simulation();
  std::printf("tightfit optimize: %d garment vertices, %d triangles, %zu pieces; terms:",
              sim.garment().num_garment_vertices(),
              static_cast<int>(sim.garment().topology->garment_triangles.rows()),
              sim.garment().pattern.pieces.size());
  const std::vector<std::string>& names = s.optimization->term_names();
  for (size_t k = 0; k < names.size(); ++k)
    std::printf(" %s (w %g)", names[k].c_str(), s.optimization->objective().entries()[k].weight);
  std::printf("\n");
  return s;
}

/// The closing lines: the objective of the returned design, the files, and last the
/// rule that ended the run, in words.
void print_summary(const OptimizationResult& result, const std::vector<OptimizationIteration>& h,
                   const fs::path& out, const api::WrittenOutputs& written) {
  std::printf("  objective %.6e -> %.6e (iteration %d%s) in %d iterations (%.1f s)\n",
              h.front().value, result.final_value, result.best_iteration,
              result.best_after_remesh ? ", after its remeshing" : "", result.iterations,
              h.back().seconds);
  if (result.best_restored)
    std::printf(
        "  the last iteration ended at %.6e, above the best design: the outputs hold the best "
        "one (iteration %d); checkpoint.json holds the last one\n",
        result.last_value, result.best_iteration);
  for (const auto& f : written.files) std::printf("  %s\n", (out / f).c_str());
  print_fit_summary(written.result, out / "report.html");
  std::printf("  stopped (%s): %s\n", stop_rule_name(result.rule), result.stop_reason.c_str());
}

}  // namespace

void run_optimize(const OptimizeRequest& request) {
  OptimizeSetup s = load_optimize_setup(request);
  api::Optimization& optimization = *s.optimization;
  const int checkpoint_every = s.scene->optimization().checkpoint_every;
  const fs::path out(request.out_dir);
  const bool resuming = !request.resume_dir.empty();
  if (resuming) {
    const fs::path file = fs::path(request.resume_dir) / "checkpoint.json";
    optimization.resume(file);
    std::printf("  resuming from %s at iteration %d\n", file.c_str(),
                optimization.checkpoint().iteration);
  } else {
    std::printf("  initial equilibrium...\n");
    std::fflush(stdout);
  }
  std::printf("  %d design parameters (boundary points of %zu pieces)\n",
              optimization.num_parameters(), s.scene->simulation().garment().pattern.pieces.size());

  const fs::path checkpoint_file = out / "checkpoint.json";
  OutputDirectory& folder = *s.folder;
  const auto publish_history = [&](int best) {
    folder.publish("history.json", [&](const fs::path& file) {
      write_json_atomically(file, optimization.history_json(best), 2);
    });
  };
  const auto publish_checkpoint = [&] {
    folder.publish("checkpoint.json",
                   [&](const fs::path& file) { optimization.write_checkpoint(file); });
  };
  // A solver failure from here on (a non-finite state, a NaN refused by a writer, see
  // common/finite_output.hpp) names the stage it happened in and the last good
  // checkpoint, the one a --resume continues from.
  std::string stage = kStartOfRun;
  LastCheckpoint last;
  if (resuming)
    last = {fs::path(request.resume_dir) / "checkpoint.json", optimization.checkpoint().iteration,
            true};
  try {
    // Ctrl-C / SIGTERM: the current iteration finishes, then the run stops and writes the
    // checkpoint and the outputs of the returned pattern as after a normal stop.
    const InterruptGuard interrupts;
    OptimizeProgress progress(optimization.term_names(),
                              optimization.optimizer().options().max_iterations, request.terse);
    const OptimizationResult result = optimization.run(
        [&](const OptimizationIteration& it) {
          progress.print(it);
          stage = "writing history.json and checkpoint.json after iteration " +
                  std::to_string(it.iteration);
          publish_history(optimization.best_iteration_so_far());
          if (it.iteration % checkpoint_every == 0) {
            publish_checkpoint();
            last = {checkpoint_file, it.iteration, false};
          }
          stage = "iteration " + std::to_string(it.iteration + 1);
          return true;
        },
        [] { return interrupt_requested(); });
    stage = "writing the final checkpoint";
    publish_checkpoint();
    publish_history(result.best_iteration);
    last = {checkpoint_file, optimization.checkpoint().iteration, false};
    stage = "writing the outputs of iteration " + std::to_string(result.best_iteration);
    // The report comes last in write_fit_run_outputs: it needs the viewer's npm packages,
    // and its failure must not cost the rest.
    const api::WrittenOutputs written =
        api::write_optimization_outputs(optimization, result, folder.staging());
    folder.commit();  // all at once (common/output_directory.hpp)
    print_summary(result, optimization.history(), out, written);
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
        report_kept_failure(request.keep_failed, request.force, request.scene_file,
                            s.scene->loaded_scene(), s.scene->simulation(), e.what());
      } catch (const std::exception& kept) {
        std::printf("  the failed state could not be kept: %s\n", kept.what());
      }
    }
    if (!last.file.empty() && !last.resumed) folder.keep_published();  // resumable
    throw SolverError(failure_message(stage, e.what(), last, request));
  }
}

}  // namespace tightfit::app
