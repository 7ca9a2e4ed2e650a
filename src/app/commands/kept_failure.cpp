#include "kept_failure.hpp"

#include <cstdio>

#include "run_outputs.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::app {
namespace {

/// A per-vertex force map as PLY vertex fields: |f| (N) and f (N, 3 columns).
PlyAttributes force_fields(const Points3& forces) {
  PlyAttributes a;
  a.vertex_fields.push_back({"residual_n", forces.rowwise().norm()});
  a.vertex_fields.push_back({"residual_force", forces});
  return a;
}

}  // namespace

void check_keep_failed_folder(const std::string& keep_failed, const std::string& out_dir) {
  namespace fs = std::filesystem;
  if (!keep_failed.empty() && fs::weakly_canonical(fs::absolute(keep_failed)) ==
                                  fs::weakly_canonical(fs::absolute(out_dir)))
    throw InputError("--keep-failed", "must name another folder than --out (" + out_dir + ")");
}

std::vector<std::string> keep_failed_state(const std::filesystem::path& dir, bool force,
                                           const std::string& scene_file, const LoadedScene& scene,
                                           GarmentSimulation& sim, const std::string& message) {
  OutputDirectory failed(dir, force, "simulate");
  EmbeddedEquilibrium& problem = sim.problem();
  const VecX g = problem.gradient();
  const Points3 garment_forces = problem.garment_residual_forces();
  const Points3 body_forces = problem.body_residual_forces();
  const NewtonOptions& o = sim.newton().options();
  RunState state = make_run_state("simulate", scene.spec, sim.garment(), problem.state());
  nlohmann::json& result = state.result;
  result["run"] = run_identity_json("simulate");
  result["scene"] = scene_file;
  result["newton"] = {{"converged", false},
                      {"message", message},
                      {"final_force_residual_n", problem.force_norm(g)},
                      {"force_tolerance_n", o.force_tolerance(problem.force_scale())}};
  result["failure"] = {{"largest_force", problem.locate_largest_force(g)},
                       {"garment_residual_max_n", garment_forces.rowwise().norm().maxCoeff()},
                       {"body_residual_max_n", body_forces.rowwise().norm().maxCoeff()}};
  result["compute"] = compute_json();
  std::vector<std::string> files = write_fit_run_outputs(failed.staging(), sim, sim.analyze(),
                                                         scene.spec.pressure_operator, state);
  TriMesh garment{sim.garment_positions(), sim.garment().topology->garment_triangles};
  write_ply(failed.file("garment_residual.ply"), garment, force_fields(garment_forces));
  const int surface_vertices = scene.body.surface.num_vertices();
  TriMesh body{sim.body_positions().topRows(surface_vertices), scene.body.surface.faces};
  write_ply(failed.file("body_residual.ply"), body,
            force_fields(body_forces.topRows(surface_vertices)));
  return failed.commit();
}

void report_kept_failure(const std::string& keep_failed, bool force, const std::string& scene_file,
                         const LoadedScene& scene, GarmentSimulation& sim,
                         const std::string& message) {
  for (const auto& f : keep_failed_state(keep_failed, force, scene_file, scene, sim, message))
    std::printf("  %s/%s\n", keep_failed.c_str(), f.c_str());
  std::printf(
      "  the last state of the failed solve is in %s (garment_residual.ply, "
      "body_residual.ply: the unbalanced force per vertex; report.html)\n",
      keep_failed.c_str());
  std::fflush(stdout);
}

}  // namespace tightfit::app
