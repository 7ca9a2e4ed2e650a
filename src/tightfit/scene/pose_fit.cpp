#include "tightfit/scene/pose_fit.hpp"

#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/design/adjoint_gradient.hpp"
#include "tightfit/objectives/sliding_objective.hpp"

namespace tightfit {

double scene_friction(const SceneSpec& scene) {
  const nlohmann::json& o = scene.optimize;
  if (o.is_object() && o.contains("objectives") && o["objectives"].is_object() &&
      o["objectives"].contains("sliding") && o["objectives"]["sliding"].is_object() &&
      o["objectives"]["sliding"].contains("friction") &&
      o["objectives"]["sliding"]["friction"].is_number())
    return o["objectives"]["sliding"]["friction"].get<double>();
  return 0.3;
}

std::vector<PoseFit> pose_fits(const GarmentSimulation& sim, const SceneSpec& scene) {
  std::vector<PoseFit> fits;
  if (!scene.rig || scene.poses.empty()) return fits;
  const Body& body = sim.body();
  const PointWeights weights = body_skin_weights(body, scene.rig->weights);
  std::vector<PoseMotions> motions;
  std::vector<PosedBody> posed;
  for (const ScenePose& pose : scene.poses) {
    const auto bones = pose_skeleton(scene.rig->skeleton, pose.rotations, pose.origin);
    posed.push_back(pose_body(body, sim.body_positions(), weights, bones, scene.rig->skinning));
    motions.push_back({pose.name, posed.back().motions});
  }
  const SlidingObjective sliding(sim.garment(), sim.materials(), sim.surface(), body.num_vertices(),
                                 motions, scene_friction(scene));
  const SimulationDesignState ds(sim);
  for (std::size_t i = 0; i < scene.poses.size(); ++i) {
    const SlidingObjective::PoseView pv = sliding.pose_view(ds.view(), static_cast<int>(i));
    const PosedGarment& pg = pv.garment;
    PoseFit fit;
    fit.name = scene.poses[i].name;
    fit.origin = scene.poses[i].origin;
    fit.garment = Eigen::Map<const Points3>(pg.x.data(), pg.x.size() / 3, 3);
    fit.garment_normals.resize(fit.garment.rows(), 3);
    for (Eigen::Index j = 0; j < fit.garment.rows(); ++j)
      fit.garment_normals.row(j) =
          Vec3(pg.xu.row(j)).cross(Vec3(pg.xv.row(j))).normalized().transpose();
    fit.body = posed[i].positions;
    fit.normal = pv.forces.normal;
    fit.tangential = pv.forces.tangential;
    fit.excess = pv.forces.excess;
    fit.volume_ratio = posed[i].volume_ratio;
    fit.min_volume_ratio = posed[i].min_volume_ratio;
    fit.max_volume_ratio = posed[i].max_volume_ratio;
    fit.inverted_tets = posed[i].inverted_tets;
    fits.push_back(std::move(fit));
  }
  return fits;
}

}  // namespace tightfit
