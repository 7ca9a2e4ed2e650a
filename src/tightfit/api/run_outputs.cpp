#include "tightfit/api/run_outputs.hpp"

#include <future>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/version.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/patterns/outputs.hpp"
#include "tightfit/patterns/scene_options.hpp"
#include "tightfit/report/ease_json.hpp"
#include "tightfit/report/ease_outputs.hpp"
#include "tightfit/report/fabric_outputs.hpp"
#include "tightfit/report/pose_outputs.hpp"
#include "tightfit/report/pressure_statistics.hpp"
#include "tightfit/report/shape_outputs.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/body_up.hpp"
#include "tightfit/scene/run_state.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::api {
namespace {

/// The date on the pattern labels: the run's (result "run"/"date", UTC), so that
/// `tightfit export` of a run redraws its pattern files byte for byte; today's for a
/// state without one.
std::string pattern_date(const RunState& state) {
  const auto run = state.result.find("run");
  if (run != state.result.end() && run->is_object()) {
    const auto date = run->find("date");
    if (date != run->end() && date->is_string() && date->get<std::string>().size() >= 10)
      return date->get<std::string>().substr(0, 10);
  }
  return utc_timestamp().substr(0, 10);
}

/// The report's per-face field of the unbalanced force (N, the mean of the face's
/// vertices) at the simulation's state.
FaceField residual_force_field(const GarmentSimulation& sim) {
  const VecX residual = sim.problem().garment_residual_forces().rowwise().norm();
  const Triangles& faces = sim.garment().topology->garment_triangles;
  MatX per_face(faces.rows(), 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    per_face(f, 0) = (residual[faces(f, 0)] + residual[faces(f, 1)] + residual[faces(f, 2)]) / 3.0;
  return {std::string(fit_fields::kResidualForce), "N", per_face};
}

/// Per piece of `pattern`: the outline of the piece of the same name in `before` (empty
/// when there is none), for the report's before/after overlay.
std::vector<Points2> initial_outlines(const Pattern& pattern, const Pattern& before_pattern) {
  std::vector<Points2> outlines;
  for (const PatternPiece& piece : pattern.pieces) {
    Points2 outline;
    for (const PatternPiece& before : before_pattern.pieces)
      if (before.name == piece.name) {
        outline.resize(static_cast<Eigen::Index>(before.boundary.size()), 2);
        for (size_t i = 0; i < before.boundary.size(); ++i)
          outline.row(static_cast<Eigen::Index>(i)) = before.rest.row(before.boundary[i]);
      }
    outlines.push_back(std::move(outline));
  }
  return outlines;
}

}  // namespace

std::vector<std::string> write_fit_run_outputs(const std::filesystem::path& folder,
                                               const GarmentSimulation& sim, const FitAnalysis& fit,
                                               ShapeOperatorKind pressure_operator, RunState& state,
                                               const Pattern* initial_pattern) {
  std::vector<std::string> files = {"garment.ply", "garment.csv", "body.ply"};
  write_fit_meshes(folder, sim, fit, pressure_operator);
  const SceneSpec scene = run_state_scene(state, state.scene_file);
  // The ease table: body and pattern circumferences at the measurement levels (in
  // result.json, the report and, per piece, on the piece labels).
  EaseTable ease = fit_ease_table(sim, scene);
  // The pattern files, most of the writing, are written on a thread of their own (which
  // shares them out to the pool) while this one computes the fit's statistics and writes
  // the other files; with one thread, after them.
  std::vector<SeamStatistics> seams;
  PatternExportOptions pattern_options;
  std::future<std::vector<std::string>> pattern_files;
  if (sim.garment().pattern.pieces.size() <= kMaxPatternPieces) {
    seams = fit_seam_statistics(sim.garment(), sim.garment_positions(), sim.materials().fabric,
                                body_up_direction(scene.body));
    pattern_options = scene_pattern_export_options(scene, sim.garment(), sim.garment_positions(),
                                                   pattern_date(state));
    pattern_options.piece_notes = ease_label_lines(ease);
    pattern_files =
        std::async(thread_count() > 1 ? std::launch::async : std::launch::deferred, [&] {
          return write_pattern_files(folder, sim.garment().pattern, pattern_options, &seams);
        });
  }
  const std::vector<FitRegion> regions = resolve_fit_regions(
      sim, {scene.pressure_regions, scene.pressure_rig.get(), scene.pressure_rig_radius},
      state.scene_file);
  state.result["fabric"] = fabric_json(
      sim.materials().fabric, state.scene.value("fabric", nlohmann::json()), fit.elements, regions);
  state.result["fit"] =
      fit_statistics(sim, fit, pressure_operator, regions, body_up_direction(scene.body));
  const std::optional<ShapeComparison> shape =
      compare_to_shape_target(scene, state.scene_file, sim.garment_positions(),
                              state.initial_garment ? &*state.initial_garment : nullptr);
  if (shape) state.result["fit"]["shape"] = shape_statistics_json(*shape);
  state.result["measurements"] = ease_table_json(ease);
  PoseOutputs poses = write_pose_outputs(folder, sim, scene);
  if (!poses.files.empty()) {
    state.result["poses"] = poses.statistics;
    files.insert(files.end(), poses.files.begin(), poses.files.end());
  }
  write_json_atomically(folder / "result.json", state.result, 2);
  write_json_atomically(folder / "scene.json", state.scene, 2);
  files.insert(files.end(), {"result.json", "scene.json"});
  nlohmann::json records = nlohmann::json::array();
  if (state.command == "optimize") {
    nlohmann::json history = history_json(state.history, state.term_names);
    // The iteration whose design the run returned (PatternOptimizer's best design).
    if (const auto o = state.result.find("optimization");
        o != state.result.end() && o->is_object() && o->contains("best_iteration"))
      mark_best_iteration(history, (*o)["best_iteration"].get<int>());
    write_json_atomically(folder / "history.json", history, 2);
    files.push_back("history.json");
    records = history["iterations"];
  }
  write_run_state(folder / "state.json", state);
  files.push_back("state.json");
  FitView view = make_fit_view(sim, fit, pressure_operator, state.scene, records,
                               body_up_direction(scene.body));
  view.pressure_regions = regions;
  view.up = body_up_direction(scene.body);
  if (!poses.views.empty()) {
    view.poses = std::move(poses.views);
    view.garment_fields.push_back(
        {std::string(fit_fields::kSlidingExcess), "N", poses.worst_excess});
  }
  // A state whose solve did not converge (simulate --keep-failed): where it failed.
  if (const auto n = state.result.find("newton");
      n != state.result.end() && n->is_object() && !n->value("converged", true))
    view.garment_fields.push_back(residual_force_field(sim));
  if (shape) {
    view.garment_fields.push_back(
        shape_distance_field(sim.garment().topology->garment_triangles, shape->distance));
    view.shape_target = shape->target;
    if (state.initial_garment) view.initial_garment = *state.initial_garment;
  }
  view.summary = report_summary(state);
  view.fabric = state.result["fabric"];
  view.measurements = std::move(ease);
  if (initial_pattern && state.command == "optimize")
    view.initial_outlines = initial_outlines(view.pattern, *initial_pattern);
  const std::string scene_name = std::filesystem::path(state.scene_file).stem().string();
  write_fit_report(folder, view,
                   std::string(state.command == "optimize" ? "tightfit optimization report"
                                                           : "tightfit fit report") +
                       (scene_name.empty() ? "" : " — " + scene_name));
  files.insert(files.end(), {"report.html", "fit.glb"});
  if (pattern_files.valid()) {
    const std::vector<std::string> pattern_names = pattern_files.get();
    files.insert(files.begin() + 2, pattern_names.begin(), pattern_names.end());
  }
  return files;
}

std::vector<std::string> write_layout_run_outputs(const std::filesystem::path& folder,
                                                  const Garment& garment,
                                                  const LimitSurface& surface,
                                                  const Points3& control, const RunState& state) {
  Points3 x(garment.num_garment_vertices(), 3);
  for (int i = 0; i < garment.num_garment_vertices(); ++i)
    x.row(i) = surface.position(garment.embedding[i], control).transpose();
  const SceneSpec scene = run_state_scene(state, state.scene_file);
  std::vector<std::string> files =
      write_pattern_files(folder, garment.pattern,
                          scene_pattern_export_options(scene, garment, x, pattern_date(state)));
  write_ply(folder / "garment_embedded.ply", TriMesh{x, garment.topology->garment_triangles});
  write_json_atomically(folder / "layout.json", state.result, 2);
  write_run_state(folder / "state.json", state);
  files.insert(files.end(), {"garment_embedded.ply", "layout.json", "state.json"});
  return files;
}

void mark_best_iteration(nlohmann::json& history, int best) {
  history["best_iteration"] = best;
  for (nlohmann::json& it : history["iterations"])
    if (it.value("iteration", -1) == best) it["best"] = true;
}

nlohmann::json run_identity_json(const std::string& command) {
  return {{"command", command}, {"version", tightfit_version()}, {"date", utc_timestamp()}};
}

nlohmann::json report_summary(const RunState& state) {
  nlohmann::json s = {{"command", state.command}, {"scene", state.scene_file}};
  const nlohmann::json& r = state.result;
  if (r.contains("run") && r["run"].is_object())
    for (const char* key : {"version", "date"})
      if (r["run"].contains(key)) s[key] = r["run"][key];
  if (const auto o = r.find("optimization"); o != r.end() && o->is_object()) {
    const bool interrupted = o->value("interrupted", false);
    s["status"] = interrupted                    ? "interrupted"
                  : o->value("converged", false) ? "converged"
                                                 : "stopped";
    for (const char* key :
         {"stop_reason", "iterations", "objective_initial", "objective_final", "force_residual_n"})
      if (o->contains(key)) s[key] = (*o)[key];
    if (o->contains("seconds_optimization")) s["seconds"] = (*o)["seconds_optimization"];
  } else if (const auto n = r.find("newton"); n != r.end() && n->is_object()) {
    s["status"] = n->value("converged", false) ? "converged" : "not converged";
    if (n->contains("message")) s["stop_reason"] = (*n)["message"];
    if (n->contains("iterations")) s["newton_iterations"] = (*n)["iterations"];
    if (n->contains("final_force_residual_n"))
      s["force_residual_n"] = (*n)["final_force_residual_n"];
    if (n->contains("force_tolerance_n")) s["force_tolerance_n"] = (*n)["force_tolerance_n"];
    if (r.contains("seconds") && r["seconds"].contains("total"))
      s["seconds"] = r["seconds"]["total"];
  }
  return s;
}

nlohmann::json compute_json() {
  const BlasInfo blas = blas_info();
  return {{"threads", thread_count()},
          {"blas",
           {{"name", blas.name},
            {"library", blas.library},
            {"config", blas.config},
            {"threads", blas.threads},
            {"thread_timeout", blas.thread_timeout}}}};
}

}  // namespace tightfit::api
