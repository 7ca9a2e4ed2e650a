#pragma once
/// Pattern optimization (paper Sec. 4) of a scene with an "optimize" section: what
/// `tightfit optimize` runs, as a thin layer over scene/optimization_setup.hpp
/// (build_objective), design/optimization_problem.hpp (DesignProblem) and
/// design/pattern_optimizer.hpp (PatternOptimizer), with its output files
/// (api/run_outputs.hpp).
///
///   api::Scene scene = api::Scene::read("examples/optimize_sleeve_stretch.json");
///   api::Optimization optimization(scene);
///   const OptimizationResult result = optimization.run(
///       [](const OptimizationIteration& it) { return it.iteration < 10; });
///   api::write_optimization_outputs(optimization, result, "out");
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tightfit/api/scene.hpp"
#include "tightfit/api/simulate.hpp"
#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"

namespace tightfit::api {

/// Called after each accepted iteration (and for iteration 0, the initial pattern, when
/// a run starts fresh), with the optimizer's checkpoint() current. Returns whether the
/// run goes on: false stops it after this iteration, whose pattern and equilibrium the
/// scene's simulation then holds (OptimizationResult::interrupted is set).
using IterationObserver = std::function<bool(const OptimizationIteration& iteration)>;

struct OptimizeOptions {
  /// Overrides the scene's optimize/max_iterations when ≥ 0.
  int max_iterations = -1;
  /// s of wall time for the run; overrides the scene's optimize/time_limit when ≥ 0.
  double time_limit = -1.0;
};

/// One optimization of a scene's pattern. Holds references to the scene, which must
/// outlive it; not movable (the optimizer refers to its problem).
class Optimization {
 public:
  /// Loads the scene when needed and builds the objective of its "optimize" section
  /// (InputError when it has none or it is invalid; a shape target that cannot be read),
  /// the design problem and the optimizer.
  explicit Optimization(Scene& scene, const OptimizeOptions& options = {});
  Optimization(const Optimization&) = delete;
  Optimization& operator=(const Optimization&) = delete;
  ~Optimization();

  /// Continues from the checkpoint file `file` (written by write_checkpoint, e.g. a
  /// run's checkpoint.json) of the same scene instead of the initial pattern. Call before
  /// run(). InputError naming `file` when it cannot be read, does not fit the scene, or
  /// was written for other inputs (the scene or a file it reads changed: inputs()).
  void resume(const std::filesystem::path& file);

  /// Writes the optimizer's checkpoint() with the run's inputs() into `file`,
  /// atomically (scene/checkpoint_inputs.hpp).
  void write_checkpoint(const std::filesystem::path& file) const;
  /// history.json's document: the accepted iterations (history()) with iteration `best`
  /// marked ("best_iteration" at the top, "best": true on its record).
  nlohmann::json history_json(int best) const;
  /// The iteration of the lowest objective so far, after remeshings too: the best design
  /// while the run goes on (the run's result says which one it returns).
  int best_iteration_so_far() const;
  /// The scene's inputs (Scene::inputs_json) once it was loaded, as every checkpoint of
  /// this run records them.
  const nlohmann::json& inputs() const { return inputs_; }

  /// Runs the optimizer until a stopping rule of the scene's optimizer settings, until
  /// `on_iteration` returns false, or until `stop_requested` (polled before each
  /// iteration and between the trials of a line search; e.g. interrupt_requested of
  /// common/interrupt.hpp) returns true. The scene's simulation then holds the last
  /// accepted pattern and its equilibrium. Throws SolverError when the initial
  /// equilibrium cannot be found (PatternOptimizer::run).
  OptimizationResult run(const IterationObserver& on_iteration = {},
                         const std::function<bool()>& stop_requested = {});

  Scene& scene() { return scene_; }
  /// The objective's terms (names as in history.json), in order, and their weights.
  const std::vector<std::string>& term_names() const { return names_; }
  const DesignTermSum& objective() const { return *objective_; }
  /// Number of design parameters (the boundary points of the pieces).
  int num_parameters() const { return problem_->num_parameters(); }
  /// The accepted iterations so far (from the checkpoint's on when resumed).
  const std::vector<OptimizationIteration>& history() const { return optimizer_->history(); }
  /// The state after the last accepted iteration (what write_checkpoint saves).
  OptimizationCheckpoint checkpoint() const { return optimizer_->checkpoint(); }
  /// Whether resume() was called.
  bool resumed() const { return resumed_; }
  /// The garment at the initial equilibrium (for the report's shape silhouettes); unknown
  /// (empty) for a resumed run.
  const std::optional<TriMesh>& initial_garment() const { return initial_garment_; }

  DesignProblem& problem() { return *problem_; }
  PatternOptimizer& optimizer() { return *optimizer_; }

 private:
  Scene& scene_;
  OptimizationSpec spec_;
  std::shared_ptr<DesignTermSum> objective_;
  std::vector<std::string> names_;
  std::unique_ptr<DesignProblem> problem_;
  std::unique_ptr<PatternOptimizer> optimizer_;
  std::optional<TriMesh> initial_garment_;
  nlohmann::json inputs_;
  bool resumed_ = false;
};

/// result.json's "optimization" member of a run that ended with `result`: whether it
/// converged or was interrupted, the rule that ended it ("stop_rule", and "stop_reason"
/// in words), its iterations, the best (returned) iteration, the objective and its terms
/// at the start and of the returned design, the gradient norms, the number of design
/// parameters, the force residual of the equilibrium (N), the optimization's seconds
/// and, when the stop rule checked it, the adjoint gradient against finite differences.
nlohmann::json optimization_result_json(Optimization& optimization,
                                        const OptimizationResult& result);

/// Writes the outputs of an optimization that ended with `result` into `folder` (which
/// must exist): the pattern files of the optimized pattern, the fit at its equilibrium
/// (garment.ply, body.ply, report.html with the objective history and the before/after
/// outlines, fit.glb), result.json, scene.json, history.json and state.json
/// (write_fit_run_outputs), and checkpoint.json (with the run's inputs). Analyzes the fit
/// first. Each file is written atomically (for all of them or none: OutputDirectory,
/// see simulate.hpp).
WrittenOutputs write_optimization_outputs(Optimization& optimization,
                                          const OptimizationResult& result,
                                          const std::filesystem::path& folder);

}  // namespace tightfit::api
