/// `tightfit export DIR [--out OUT]`: regenerates the output files of a `simulate`,
/// `layout` or `optimize` run from DIR/state.json without solving again.
///
/// The scene is rebuilt from the document saved in the state (body, limit surface,
/// garment); the saved pattern, garment embedding and body positions are installed in
/// the simulation and checked against the rebuilt garment (InputError on a mismatch).
/// The state of a run that remeshed pieces holds its complete pattern: the garment is
/// welded from it instead of the scene's layout (scene/run_state.hpp, run_state_garment).
/// For equilibrium runs the force residual of the saved state is recomputed and printed.
/// OUT (default DIR) is replaced as a whole when the export succeeds; when OUT is DIR,
/// files that export does not regenerate (e.g. checkpoint.json) are kept.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "command_registry.hpp"
#include "run_outputs.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/run_state.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

/// Regenerates the fit of a simulate/optimize state into `folder`; returns the files.
std::vector<std::string> export_fit(const LoadedScene& scene, const Garment& garment,
                                    RunState& state, const fs::path& folder) {
  auto sim = make_simulation(scene);
  if (state.pattern) {
    sim->replace_garment(garment, state.state);
  } else {
    sim->set_rest_positions(stacked_rest_positions(state));
    sim->set_state(state.state);
  }
  EmbeddedEquilibrium& problem = sim->problem();
  const double residual = problem.force_norm(problem.gradient());
  const NewtonOptions& newton = scene.spec.newton;
  const double tolerance = newton.force_tolerance(problem.force_scale());
  std::printf("  force residual of the saved state %.3e N (tolerance %.3e N): %s\n", residual,
              tolerance,
              residual <= tolerance ? "an equilibrium"
                                    : "NOT an equilibrium (the scene, its files or tightfit "
                                      "changed since the run?)");
  const FitAnalysis fit = sim->analyze();
  return write_fit_run_outputs(folder, *sim, fit, scene.spec.pressure_operator, state,
                               &scene.garment.pattern);
}

/// Regenerates the outputs of a layout state into `folder`; returns the files.
std::vector<std::string> export_layout(const LoadedScene& scene, const Garment& garment,
                                       const RunState& state, const fs::path& folder) {
  const Points3 control = state.state.body.topRows(scene.body.num_surface_vertices());
  return write_layout_run_outputs(folder, garment, *scene.surface, control, state);
}

/// Copies the entries of `from` that `to` does not have (files export does not make).
void run_export(const std::string& dir, const std::string& out_option, bool force) {
  const fs::path state_file = fs::path(dir) / "state.json";
  const std::string source = state_file.string();
  // Everything is read and checked before the output folder is touched.
  RunState state = read_run_state(state_file);
  std::printf("tightfit export: %s run of %s\n", state.command.c_str(), state.scene_file.c_str());
  std::fflush(stdout);
  auto scene = load_scene(run_state_scene(state, source));
  const Garment garment =
      run_state_garment(state, scene->garment, scene->body, scene->surface->num_faces(), source);
  if (state.command == "layout" && scene->garment.pattern.pieces.size() > kMaxPatternPieces)
    throw InputError(source, "/command: a layout run of a garment without a pattern");

  const fs::path out_dir = out_option.empty() ? fs::path(dir) : fs::path(out_option);
  OutputDirectory out(out_dir, force, "export");
  const std::vector<std::string> files = state.command == "layout"
                                             ? export_layout(*scene, garment, state, out.staging())
                                             : export_fit(*scene, garment, state, out.staging());
  out.commit();
  for (const auto& f : files) std::printf("  %s\n", (out.target() / f).c_str());
}

/// `tightfit export DIR [--out OUT] [--force]`.
struct ExportOptions {
  std::string dir;
  std::string out;
  bool force = false;
};

const CommandRegistration kExport{
    "export", [](CLI::App& root) {
      auto [cmd, o] = add_command<ExportOptions>(
          root,
          {"export",
           "Regenerate the outputs of a simulate, layout or optimize run from DIR/state.json "
           "without solving again: the pattern files, and for simulate/optimize runs report.html "
           "(with the objective history of optimize runs), fit.glb, garment.ply, body.ply, "
           "result.json; for layout runs garment_embedded.ply and layout.json. Prints the force "
           "residual of the saved state.",
           "Example:\n  tightfit export out/pants --out out/pants_again"},
          [](const ExportOptions& options) {
            run_export(options.dir, options.out, options.force);
          });
      cmd.add_option("dir", o.dir, "Output folder of an earlier run (holds state.json)")
          ->required();
      // --out is optional here: DIR itself by default.
      cmd.add_option("--out", o.out, std::string("Default DIR. ") + kOutHelp);
      cmd.add_flag("--force", o.force, kForceHelp);
    }};

}  // namespace
}  // namespace tightfit::app
