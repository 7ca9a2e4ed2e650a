#include "tightfit/scene/optimization_setup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/surface_sampling.hpp"
#include "tightfit/objectives/all_poses_term.hpp"
#include "tightfit/objectives/directional_stretch_objective.hpp"
#include "tightfit/objectives/pinned_traction_regularizer.hpp"
#include "tightfit/objectives/pressure_objective.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/regularizer_corner_angle.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/regularizer_smoothness.hpp"
#include "tightfit/objectives/seam_traction_objective.hpp"
#include "tightfit/objectives/shape_objective.hpp"
#include "tightfit/objectives/sliding_objective.hpp"
#include "tightfit/objectives/stretch_objective.hpp"

namespace tightfit {
namespace {

/// The skinning motion of every body vertex in every pose of the scene (those named
/// in `names`, or all when it is empty); a pose that inverts a tet of the body is an
/// InputError naming it.
std::vector<PoseMotions> pose_motions(const DesignPoses& poses, const Body& body,
                                      const std::vector<std::string>& names = {}) {
  const PointWeights weights = body_skin_weights(body, *poses.rig);
  std::vector<PoseMotions> out;
  for (const auto& [name, bones] : poses.bone_motions) {
    if (!names.empty() && std::find(names.begin(), names.end(), name) == names.end()) continue;
    const PosedBody posed = pose_body(body, body.volume.vertices, weights, bones, poses.skinning);
    check_posed_body(posed, body, name, poses.source);
    out.push_back({name, posed.motions});
  }
  return out;
}

}  // namespace

ImlsSurface read_shape_target(const ShapeObjectiveSpec& spec) {
  const TriMesh mesh = read_tri_mesh(spec.target);
  if (!(spec.radius > 0.0) || !std::isfinite(spec.radius))
    throw InputError(spec.target.string(), "the IMLS radius must be positive");
  const double spacing = 0.5 * spec.radius;
  const std::int64_t count = count_surface_samples(mesh, spacing);
  if (count == 0) throw InputError(spec.target.string(), "the shape target has no faces");
  if (count > kMaxShapeTargetPoints)
    throw InputError(spec.target.string(),
                     "the shape target would need " + std::to_string(count) +
                         " points at half the IMLS radius (" + std::to_string(spec.radius) +
                         " m), more than " + std::to_string(kMaxShapeTargetPoints) +
                         ": use a larger radius (and check the mesh's units)");
  OrientedPoints samples = sample_surface(mesh, spacing);
  return ImlsSurface(std::move(samples.points), std::move(samples.normals), spec.radius);
}

OptimizationScene read_optimization_scene(const std::string& file) {
  OptimizationScene s;
  s.scene = read_scene(file);
  s.optimization = scene_optimization(s.scene);
  return s;
}

OptimizationSpec scene_optimization(const SceneSpec& scene) {
  const std::string& file = scene.file;
  if (scene.optimize.is_null())
    throw InputError(file, "/optimize: missing (this command needs an \"optimize\" section)");
  OptimizationSpec o = parse_optimization_spec(scene.optimize, file, "/optimize", scene.base_dir);
  if (auto& pressure = o.pressure) {
    if (pressure->scene_regions && scene.pressure_regions.empty())
      throw InputError(file,
                       "/optimize/objectives/pressure: give a range (min_pa/max_pa or "
                       "min_mmhg/max_mmhg) or the targets in /pressure/regions");
    if (!pressure->scene_regions && !scene.pressure_regions.empty())
      throw InputError(file,
                       "/optimize/objectives/pressure: the scene has /pressure/regions; "
                       "give the targets there or here, not both");
    pressure->regions = scene.pressure_regions;
    pressure->regions_source = file;
    pressure->rig = scene.pressure_rig;
    pressure->rig_radius = scene.pressure_rig_radius;
  }
  const bool posed_terms = o.sliding || (o.stretch && o.stretch->all_poses) ||
                           (o.directional_stretch && o.directional_stretch->bounds.all_poses) ||
                           (o.pressure && o.pressure->all_poses);
  if (posed_terms) {
    if (!scene.rig || scene.poses.empty())
      throw InputError(
          file,
          "/optimize/objectives: a term asks for poses (sliding, or \"poses\": \"all\") "
          "but the scene has none (give \"rig\" and \"poses\")");
    o.poses.rig = std::shared_ptr<const SkinWeights>(scene.rig, &scene.rig->weights);
    o.poses.skinning = scene.rig->skinning;
    o.poses.source = file;
    for (const ScenePose& p : scene.poses)
      o.poses.bone_motions.emplace_back(p.name,
                                        pose_skeleton(scene.rig->skeleton, p.rotations, p.origin));
  }
  if (o.sliding)
    for (const std::string& name : o.sliding->poses)
      if (std::none_of(scene.poses.begin(), scene.poses.end(),
                       [&](const ScenePose& p) { return p.name == name; }))
        throw InputError(
            file, "/optimize/objectives/sliding/poses: the scene has no pose \"" + name + "\"");
  return o;
}

std::shared_ptr<DesignTermSum> build_objective(const OptimizationSpec& spec,
                                               const GarmentSimulation& sim) {
  const Garment& g = sim.garment();
  auto sum = std::make_shared<DesignTermSum>();
  auto add = [&](double weight, auto make) {
    if (weight > 0.0) sum->add(make(), weight);
  };
  std::vector<PoseMotions> all_poses;  // computed once, when a term needs them
  auto in_poses = [&](bool all,
                      std::shared_ptr<const DesignTerm> term) -> std::shared_ptr<const DesignTerm> {
    if (!all) return term;
    if (all_poses.empty()) all_poses = pose_motions(spec.poses, sim.body());
    return std::make_shared<AllPosesTerm>(std::move(term), sim.surface(), all_poses);
  };
  if (spec.stretch)
    add(spec.stretch->weight, [&] {
      StretchBounds b;
      b.min_stretch = spec.stretch->min_stretch;
      b.max_stretch = spec.stretch->max_stretch.value_or(std::numeric_limits<double>::infinity());
      return in_poses(spec.stretch->all_poses, std::make_shared<StretchObjective>(g, b));
    });
  if (spec.directional_stretch)
    add(spec.directional_stretch->bounds.weight, [&] {
      const StretchObjectiveSpec& s = spec.directional_stretch->bounds;
      StretchBounds b;
      b.min_stretch = s.min_stretch;
      b.max_stretch = s.max_stretch.value_or(std::numeric_limits<double>::infinity());
      return in_poses(s.all_poses,
                      std::make_shared<DirectionalStretchObjective>(
                          g,
                          spec.directional_stretch->across_grain ? FabricDirection::kAcrossGrain
                                                                 : FabricDirection::kAlongGrain,
                          b));
    });
  if (spec.shape)
    add(spec.shape->weight, [&] {
      std::vector<int> vertices;  // empty: all
      if (spec.shape->skip_pinned) {
        vertices = unpinned_vertices(g);
        if (vertices.empty())
          throw InputError(spec.shape->target.string(),
                           "the shape objective has no unpinned garment vertex to act on");
      }
      return std::make_shared<ShapeObjective>(read_shape_target(*spec.shape),
                                              g.num_garment_vertices(), vertices,
                                              shape_vertex_weights(g, spec.resolution));
    });
  if (spec.pressure)
    add(spec.pressure->weight, [&]() -> std::shared_ptr<const DesignTerm> {
      if (!spec.pressure->scene_regions)
        return in_poses(
            spec.pressure->all_poses,
            std::make_shared<PressureObjective>(g, sim.materials().fabric, spec.pressure->min_pa,
                                                spec.pressure->max_pa));
      const std::string& source = spec.pressure->regions_source;
      PressureRegions regions(g, spec.pressure->regions, source, spec.pressure->rig.get(),
                              spec.pressure->rig_radius);
      const Points3& x = sim.garment_positions();
      regions.check_covered(Eigen::Map<const VecX>(x.data(), x.size()), source);
      return in_poses(spec.pressure->all_poses, std::make_shared<PressureObjective>(
                                                    g, sim.materials().fabric, std::move(regions)));
    });
  if (spec.seam_traction)
    add(spec.seam_traction->weight,
        [&] { return std::make_shared<SeamTractionObjective>(g, sim.materials().fabric); });
  if (spec.sliding)
    add(spec.sliding->weight, [&] {
      return std::make_shared<SlidingObjective>(
          g, sim.materials(), sim.surface(), sim.body().num_vertices(),
          pose_motions(spec.poses, sim.body(), spec.sliding->poses), spec.sliding->friction,
          sliding_vertex_weights(g, spec.resolution));
    });
  const RegularizerWeights& w = spec.regularizers;
  add(w.seam_length, [&] {
    return std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(g, spec.resolution));
  });
  add(w.boundary_spacing, [&] {
    return std::make_shared<EdgeLengthDifferenceTerm>(even_spacing_regularizer(g, spec.resolution));
  });
  add(w.boundary_smoothness, [&] { return std::make_shared<BoundarySmoothnessRegularizer>(g); });
  add(w.corner_angle, [&] { return std::make_shared<CornerAngleRegularizer>(g); });
  add(w.compactness, [&] {
    return std::make_shared<CompactnessRegularizer>(g, w.compactness_options, spec.resolution);
  });
  add(w.pinned_traction, [&] {
    return std::make_shared<PinnedTractionRegularizer>(g, sim.materials(), sim.surface(),
                                                       spec.resolution);
  });
  return sum;
}

}  // namespace tightfit
