#include "tightfit/report/pose_outputs.hpp"

#include <algorithm>

#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/design/adjoint_gradient.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/objectives/sliding_objective.hpp"
#include "tightfit/report/simulation_outputs.hpp"

namespace tightfit {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

double scene_friction(const SceneSpec& scene) {
  const nlohmann::json& o = scene.optimize;
  if (o.is_object() && o.contains("objectives") && o["objectives"].is_object() &&
      o["objectives"].contains("sliding") && o["objectives"]["sliding"].is_object() &&
      o["objectives"]["sliding"].contains("friction") &&
      o["objectives"]["sliding"]["friction"].is_number())
    return o["objectives"]["sliding"]["friction"].get<double>();
  return 0.3;
}

PoseOutputs write_pose_outputs(const std::filesystem::path& folder, const GarmentSimulation& sim,
                               const SceneSpec& scene) {
  PoseOutputs out;
  if (!scene.rig || scene.poses.empty()) return out;
  const Body& body = sim.body();
  const PointWeights weights = body_skin_weights(body, scene.rig->weights);
  std::vector<PoseMotions> motions;
  std::vector<PosedBody> posed;
  for (const ScenePose& pose : scene.poses) {
    const auto bones = pose_skeleton(scene.rig->skeleton, pose.rotations, pose.origin);
    posed.push_back(pose_body(body, sim.body_positions(), weights, bones, scene.rig->skinning));
    motions.push_back({pose.name, posed.back().motions});
  }
  const double friction = scene_friction(scene);
  const SlidingObjective sliding(sim.garment(), sim.materials(), sim.surface(), body.num_vertices(),
                                 motions, friction);
  const SimulationDesignState ds(sim);
  const Triangles& faces = sim.garment().topology->garment_triangles;
  out.worst_excess = VecX::Zero(faces.rows());
  std::vector<char> pinned(static_cast<std::size_t>(sim.garment().num_garment_vertices()), 0);
  for (int v : sim.garment().topology->pinned) pinned[static_cast<std::size_t>(v)] = 1;
  for (std::size_t i = 0; i < scene.poses.size(); ++i) {
    const int pose = static_cast<int>(i);
    const SlidingObjective::PoseView pv = sliding.pose_view(ds.view(), pose);
    const SlidingForces& f = pv.forces;
    const PosedGarment& pg = pv.garment;
    const TriMesh mesh{Eigen::Map<const Points3>(pg.x.data(), pg.x.size() / 3, 3),
                       sim.garment().topology->garment_triangles};
    PlyAttributes attributes;
    attributes.vertex_fields = {
        {"sliding_excess_n", f.excess}, {"tangential_n", f.tangential}, {"pressing_n", f.normal}};
    const std::string file = "garment_pose_" + scene.poses[i].name + ".ply";
    write_ply(folder / file, mesh, attributes);
    out.files.push_back(file);
    std::vector<double> excess, pressing;
    int sliding_vertices = 0;
    double value = 0.0;
    for (int j = 0; j < f.excess.size(); ++j) {
      if (pinned[static_cast<std::size_t>(j)]) continue;
      excess.push_back(f.excess[j]);
      pressing.push_back(f.normal[j]);
      value += f.excess[j] * f.excess[j];
      if (f.excess[j] > 0.0) ++sliding_vertices;
    }
    FitPose view;
    view.name = scene.poses[i].name;
    view.garment = mesh.vertices;
    view.garment_normals.resize(mesh.vertices.rows(), 3);
    for (Eigen::Index j = 0; j < mesh.vertices.rows(); ++j)
      view.garment_normals.row(j) =
          Vec3(pg.xu.row(j)).cross(Vec3(pg.xv.row(j))).normalized().transpose();
    view.body = body_limit_positions(body, sim.surface(), posed[i].positions);
    view.sliding_excess = VecX::Zero(faces.rows());
    for (Eigen::Index t = 0; t < faces.rows(); ++t)
      view.sliding_excess[t] =
          (f.excess[faces(t, 0)] + f.excess[faces(t, 1)] + f.excess[faces(t, 2)]) / 3.0;
    out.worst_excess = out.worst_excess.cwiseMax(view.sliding_excess);
    view.sliding_share =
        excess.empty() ? 0.0
                       : static_cast<double>(sliding_vertices) / static_cast<double>(excess.size());
    out.views.push_back(std::move(view));
    out.statistics.push_back(
        {{"name", scene.poses[i].name},
         {"from", scene.poses[i].origin},
         {"friction", friction},
         {"sliding_objective_n2", value},
         {"free_vertices", excess.size()},
         {"sliding_share", excess.empty() ? 0.0
                                          : static_cast<double>(sliding_vertices) /
                                                static_cast<double>(excess.size())},
         {"excess_n",
          {{"max", excess.empty() ? 0.0 : *std::max_element(excess.begin(), excess.end())},
           {"median", median(excess)}}},
         {"pressing_n_median", median(pressing)},
         {"body",
          {{"volume_ratio", posed[i].volume_ratio},
           {"tet_volume_ratio",
            {{"min", posed[i].min_volume_ratio}, {"max", posed[i].max_volume_ratio}}},
           {"inverted_tets", posed[i].inverted_tets}}},
         {"file", file}});
  }
  return out;
}

}  // namespace tightfit
