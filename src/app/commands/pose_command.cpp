/// `tightfit pose SCENE --out DIR`: the scene's body in each of its poses, to look at
/// before optimizing: DIR/body_neutral.obj, DIR/body_pose_NAME.obj per pose (surface
/// meshes, m) and DIR/poses.json (per pose: where it came from, tet volume ratios,
/// largest displacement; the weight transfer's distance to the rig).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "command_registry.hpp"
#include "run_outputs.hpp"
#include "tightfit/body/body_builder.hpp"
#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

TriMesh surface_at(const Body& body, const Points3& y) {
  return {y.topRows(body.num_surface_vertices()), body.surface.faces};
}

void run_pose(const std::string& scene_file, const std::string& out_dir, bool force) {
  const SceneSpec spec = read_scene(scene_file);
  if (!spec.rig)
    throw InputError(scene_file, "/rig: missing (tightfit pose needs a rig and poses)");
  if (spec.poses.empty()) throw InputError(scene_file, "/poses: missing or empty");
  BuildReport build;
  const Body body = build_body(spec.body, &build);
  for (const std::string& w : build.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  SkinTransferReport transfer;
  const PointWeights weights = body_skin_weights(body, spec.rig->weights, &transfer);
  std::printf(
      "tightfit pose: %d body vertices (%d tets), %zu poses, %s skinning; body within %.1f mm "
      "of the rig mesh (mean %.2f mm)\n",
      body.num_vertices(), body.volume.num_tets(), spec.poses.size(),
      skinning_method_name(spec.rig->skinning), 1e3 * transfer.max_distance,
      1e3 * transfer.mean_distance);
  nlohmann::json summary = {
      {"run", run_identity_json("pose")},
      {"scene", scene_file},
      {"skinning", skinning_method_name(spec.rig->skinning)},
      {"rig_distance_mm",
       {{"max", 1e3 * transfer.max_distance}, {"mean", 1e3 * transfer.mean_distance}}},
      {"poses", nlohmann::json::array()}};
  std::vector<std::pair<std::string, TriMesh>> meshes{{"body_neutral.obj", body.surface}};
  for (const ScenePose& pose : spec.poses) {
    for (const std::string& joint : pose.ignored_joints)
      std::fprintf(stderr,
                   "warning: pose \"%s\": joint \"%s\" of %s is not a bone of the rig; its "
                   "rotation is not used\n",
                   pose.name.c_str(), joint.c_str(), pose.origin.c_str());
    const auto bones = pose_skeleton(spec.rig->skeleton, pose.rotations, pose.origin);
    const PosedBody posed =
        pose_body(body, body.volume.vertices, weights, bones, spec.rig->skinning);
    check_posed_body(posed, body, pose.name, pose.origin);
    const double displacement =
        (posed.positions - body.volume.vertices).rowwise().norm().maxCoeff();
    summary["poses"].push_back(
        {{"name", pose.name},
         {"from", pose.origin},
         {"rotated_bones", pose.rotations.size()},
         {"volume_ratio", posed.volume_ratio},
         {"tet_volume_ratio", {{"min", posed.min_volume_ratio}, {"max", posed.max_volume_ratio}}},
         {"max_displacement_m", displacement}});
    std::printf(
        "  %-16s volume %.4f of neutral, tet volume ratios %.3f .. %.3f, moved up to %.3f m\n",
        pose.name.c_str(), posed.volume_ratio, posed.min_volume_ratio, posed.max_volume_ratio,
        displacement);
    meshes.emplace_back("body_pose_" + pose.name + ".obj", surface_at(body, posed.positions));
  }
  OutputDirectory folder(fs::path(out_dir), force, "pose");
  for (const auto& [name, mesh] : meshes) write_tri_mesh(folder.file(name), mesh);
  write_json_atomically(folder.file("poses.json"), summary, 2);
  folder.commit();
  for (const auto& [name, mesh] : meshes)
    std::printf("  %s\n", (fs::path(out_dir) / name).string().c_str());
  std::printf("  %s\n", (fs::path(out_dir) / "poses.json").string().c_str());
}

const CommandRegistration kPose{
    "pose", [](CLI::App& root) {
      auto [cmd, o] = add_command<SceneRunOptions>(
          root,
          {"pose",
           "The scene's body in each of its poses (\"rig\" and \"poses\" in the scene), to look "
           "at before optimizing: writes OUT/body_neutral.obj, OUT/body_pose_NAME.obj per pose "
           "and OUT/poses.json (volume ratios, displacements). A pose that inverts a tet is an "
           "error.",
           "Example:\n  tightfit pose examples/poses_legs_stride.json --out out/poses"},
          [](const SceneRunOptions& options) {
            run_pose(options.scene, options.out, options.force);
          });
      add_scene_run_options(cmd, o);
    }};

}  // namespace
}  // namespace tightfit::app
