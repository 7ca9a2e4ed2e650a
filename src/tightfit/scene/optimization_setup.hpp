#pragma once
/// Reading a scene file with an "optimize" section and building the weighted design
/// objective from it: what `tightfit optimize`, `tightfit check-gradient` and the
/// benchmarks share, so that a benchmark runs exactly the objective of an example.
#include <memory>
#include <string>

#include "tightfit/design/optimization_spec.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/imls_surface.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

struct OptimizationScene {
  SceneSpec scene;                ///< the scene (scene.optimize: the raw section)
  OptimizationSpec optimization;  ///< the parsed "optimize" section
};

/// Reads the scene `file` (read_scene); its "optimize" section is required and parsed
/// by scene_optimization.
OptimizationScene read_optimization_scene(const std::string& file);

/// The "optimize" section of `scene` (required) parsed by parse_optimization_spec, with
/// the scene's pressure regions and rig, and its poses for the terms that ask for them.
/// InputError naming scene.file and the JSON path when it is missing or invalid.
OptimizationSpec scene_optimization(const SceneSpec& scene);

/// The shape objective's target surface: the mesh `spec.target` sampled at half the
/// kernel radius (sample_surface: its vertices, plus points along edges and inside faces
/// where the mesh is coarser; normals interpolated from the area-weighted vertex normals),
/// kernel radius `spec.radius`. The IMLS distance is smooth only where several target
/// points lie within the radius; from a target's bare vertices it was not wherever the
/// mesh is coarser than the radius (the legs target's 13 mm median edge against a 10 mm
/// radius): the nearest-point fallback then jumped between vertices' tangent planes and
/// the optimizer's line search stalled. InputError naming the file when it cannot be
/// read, has no faces, or would need more than kMaxShapeTargetPoints samples.
ImlsSurface read_shape_target(const ShapeObjectiveSpec& spec);
/// Largest number of target points read_shape_target makes (about 200 MB with the
/// neighbour index).
inline constexpr std::int64_t kMaxShapeTargetPoints = 4'000'000;

/// The objective Σ w_j T_j of the spec for the simulation's garment: objectives first
/// (stretch, shape, pressure, seam traction, sliding), then the regularizers (seam length,
/// boundary spacing, boundary smoothness, compactness, pinned traction); terms of weight 0 are left
/// out. The shape target is read here (InputError naming the file).
std::shared_ptr<DesignTermSum> build_objective(const OptimizationSpec& spec,
                                               const GarmentSimulation& sim);

}  // namespace tightfit
