#pragma once
/// One pattern optimization run (paper Sec. 4) of a scene with an "optimize" section
/// (design/optimization_spec.hpp): what `tightfit optimize` runs, and `tightfit grade`
/// for each body.
///
/// The run returns its best design (design/pattern_optimizer.hpp): the pattern, fit and
/// report are those of the best iteration, which history.json marks ("best_iteration");
/// result.json's "optimization" says which rule ended the run ("stop_rule", and
/// "stop_reason" in words), and the last line printed repeats it.
///
/// The output folder is written DURING the run (each file atomically, so a crash leaves
/// the last complete version of every file): history.json after every iteration,
/// checkpoint.json every `checkpoint_every` iterations and at the end; at the end also
/// the optimized pattern files (pattern.svg, pattern_*.pdf, pattern.dxf, pieces.json),
/// the fit at the final equilibrium (report.html with the objective history, fit.glb,
/// garment.ply, body.ply), result.json, scene.json and state.json (the run state that
/// `tightfit export` regenerates these files from; it holds the complete pattern when
/// pieces were remeshed). A resumed run continues from RESUME/checkpoint.json (same
/// scene and objective terms), appending to the history; a checkpoint written after a
/// remeshing carries the remeshed pattern, which the run continues on.
#include <string>

namespace tightfit::app {

struct OptimizeRequest {
  std::string scene_file;   ///< scene with an "optimize" section
  std::string out_dir;      ///< output folder (common/output_directory.hpp's rule)
  std::string resume_dir;   ///< folder of the checkpoint.json to continue from; empty: none
  int max_iterations = -1;  ///< overrides optimize/max_iterations when ≥ 0
  bool force = false;       ///< write into a non-empty folder tightfit did not make
  /// Folder for the last state of an initial equilibrium that does not converge; empty:
  /// none (app/commands/kept_failure.hpp).
  std::string keep_failed;
  /// Progress rows only, without each iteration's line of term values.
  bool terse = false;
  double time_limit = -1.0;  ///< s of wall time; overrides optimize/time_limit when ≥ 0
};

/// Runs the optimization and writes its outputs (header comment). Progress goes to
/// stdout. Throws InputError for bad input (before the output folder is touched), a
/// SolverError naming the stage and the last good checkpoint, and Interrupted after
/// Ctrl-C / SIGTERM (the current iteration finishes, then the checkpoint and the outputs
/// of the last accepted pattern are written).
void run_optimize(const OptimizeRequest& request);

}  // namespace tightfit::app
