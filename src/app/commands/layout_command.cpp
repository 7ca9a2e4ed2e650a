/// `tightfit layout SCENE --out DIR`: the initial pattern pieces and the garment
/// embedded on the body, without simulating.
#include <cstdio>

#include "command_registry.hpp"
#include "run_outputs.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/patterns/outputs.hpp"
#include "tightfit/scene/loader.hpp"

namespace tightfit::app {
namespace {

void run_layout(const std::string& scene_file, const std::string& out_dir, bool force) {
  SceneSpec spec = read_scene(scene_file);  // bad input fails before the folder is touched
  OutputDirectory out(out_dir, force, "layout");
  auto scene = load_scene(std::move(spec));
  const Garment& g = scene->garment;
  if (g.pattern.pieces.size() > kMaxPatternPieces)
    throw InputError(scene_file,
                     "this garment has one piece per triangle (a cover); it has no "
                     "pattern to lay out");
  // Nothing is simulated: the state is the embedding and the body at rest.
  RunState state =
      make_run_state("layout", scene->spec, g, {g.embedding, scene->body.volume.vertices});
  nlohmann::json& report = state.result;
  report["run"] = run_identity_json("layout");  // its date is the pattern files' date
  report["scene"] = scene_file;
  report["pieces"] = g.pattern.pieces.size();
  report["seams"] = g.pattern.seams.size();
  report["garment_vertices"] = g.num_garment_vertices();
  report["pinned_garment_vertices"] = g.topology->pinned.size();
  if (scene->build) report["build"] = garment_build_report(*scene->build);
  const auto files = write_layout_run_outputs(out.staging(), g, *scene->surface,
                                              scene->body.surface.vertices, state);
  out.commit();
  std::printf("tightfit layout: %zu pieces, %zu seams, %d garment vertices\n",
              g.pattern.pieces.size(), g.pattern.seams.size(), g.num_garment_vertices());
  for (const auto& f : files) std::printf("  %s/%s\n", out.target().c_str(), f.c_str());
}

const CommandRegistration kLayout{
    "layout", [](CLI::App& root) {
      auto [cmd, o] = add_command<SceneRunOptions>(
          root,
          {"layout",
           "Flatten the scene's garment layout into pattern pieces (SVG 1:1, tiled and full-size "
           "PDF, DXF, pieces.json) and embed the garment on the body (garment_embedded.ply), "
           "without simulating. layout.json reports the flattening distortion per piece; "
           "state.json is the run state for `tightfit export`.",
           "Example:\n  tightfit layout examples/pants_legs.json --out out/pants_layout"},
          [](const SceneRunOptions& options) {
            run_layout(options.scene, options.out, options.force);
          });
      add_scene_run_options(cmd, o);
    }};

}  // namespace
}  // namespace tightfit::app
