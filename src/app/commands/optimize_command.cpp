/// `tightfit optimize SCENE --out DIR [--resume DIR] [--max-iterations N] [--time-limit S]`:
/// pattern optimization (paper Sec. 4) with the scene's "optimize" section
/// (design/optimization_spec.hpp); --max-iterations and --time-limit override its
/// max_iterations and time_limit.
///
/// Writes DIR as app/commands/optimize_run.hpp describes; `--resume DIR` continues from
/// DIR/checkpoint.json of an earlier run of the same scene.
#include <memory>
#include <string>

#include "cli_checks.hpp"
#include "command_registry.hpp"
#include "optimize_run.hpp"

namespace tightfit::app {
namespace {

const CommandRegistration kOptimize{
    "optimize", [](CLI::App& root) {
      auto* cmd = root.add_subcommand(
          "optimize",
          "Optimize the pattern boundaries (L-BFGS with adjoint gradients) for the objectives of "
          "the scene's \"optimize\" section. Writes history.json and checkpoint.json while it "
          "runs, then the pattern files (SVG, PDF, DXF, pieces.json), report.html, fit.glb, "
          "garment.ply, body.ply, result.json and state.json (the run state for "
          "`tightfit export`).");
      cmd->footer(
          "Examples:\n  tightfit optimize examples/optimize_pants_stretch.json --out out/pants\n"
          "  tightfit optimize examples/optimize_pants_stretch.json --out out/pants \\\n"
          "      --resume out/pants --max-iterations 80");
      auto scene = std::make_shared<std::string>();
      auto out = std::make_shared<std::string>();
      auto resume = std::make_shared<std::string>();
      cmd->add_option("scene", *scene, "Scene file with an \"optimize\" section")->required();
      cmd->add_option("--out", *out,
                      std::string(kOutHelp) +
                          "; history.json and checkpoint.json are "
                          "written there while the run goes on")
          ->required();
      auto force = std::make_shared<bool>(false);
      cmd->add_flag("--force", *force, kForceHelp);
      cmd->add_option("--resume", *resume,
                      "Continue from DIR/checkpoint.json of an earlier run of the same scene");
      auto max_iterations = std::make_shared<int>(-1);
      cmd->add_option("--max-iterations", *max_iterations,
                      "Stop after this many L-BFGS iterations (overrides the scene's "
                      "optimize/max_iterations)")
          ->check(non_negative_number());
      auto time_limit = std::make_shared<double>(-1.0);
      cmd->add_option("--time-limit", *time_limit,
                      "Wall-clock budget of the run in seconds: no new iteration starts after it "
                      "(overrides the scene's optimize/time_limit); the run then returns its "
                      "best design")
          ->check(non_negative_number());
      auto keep_failed = std::make_shared<std::string>();
      cmd->add_option("--keep-failed", *keep_failed,
                      "When the initial equilibrium does not converge, write its last state to "
                      "this folder: the fit outputs and garment_residual.ply / "
                      "body_residual.ply (unbalanced force per vertex, N)");
      auto terse = std::make_shared<bool>(false);
      cmd->add_flag("--terse", *terse,
                    "Progress: one row per iteration, without the values of the objective's terms");
      cmd->callback([scene, out, resume, max_iterations, time_limit, force, keep_failed, terse] {
        OptimizeRequest request;
        request.scene_file = *scene;
        request.out_dir = *out;
        request.resume_dir = *resume;
        request.max_iterations = *max_iterations;
        request.time_limit = *time_limit;
        request.force = *force;
        request.keep_failed = *keep_failed;
        request.terse = *terse;
        run_optimize(request);
      });
    }};

}  // namespace
}  // namespace tightfit::app
