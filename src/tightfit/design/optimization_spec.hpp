#pragma once
/// The "optimize" section of a scene file (read strictly with JsonFields: unknown keys
/// and wrong types are InputErrors naming the file and JSON path). SI units; stretches
/// are principal STRETCHES (1.3 = 30 % stretch), not Cauchy-Green eigenvalues.
///
///   "optimize": {
///     "objectives": {                       // at least one objective or regularizer
///       "stretch":  {"weight": 1, "min": 1.05, "max": 1.3},   // "max" optional (none)
///                                           // stretch, directional_stretch, pressure:
///                                           // "poses": "all" also in every scene pose
///       "directional_stretch": {"weight": 1, "direction": "across_grain",  // or along_grain
///                               "min": 1.3, "max": 1.3},                // "max" optional
///       "shape":    {"weight": 1, "target": "target.obj", "radius": 0.01,
///                    "vertices": "all"},    // or "unpinned": skip pinned boundary vertices
///       "pressure": {"weight": 1, "min_mmhg": 15, "max_mmhg": 25},  // or min_pa/max_pa;
///                                           // without a range: the scene's pressure regions
///       "seam_traction": {"weight": 1},
///       "sliding":  {"weight": 1, "friction": 0.3,   // Eq. 37 over the scene's poses
///                    "poses": ["contact", "flight"]} // default: all of them
///     },
///     "regularizers": {                     // weights, all optional (default 0 = off)
///       "seam_length": 1, "boundary_spacing": 0.1, "boundary_smoothness": 1e-4,
///       "corner_angle": 1e-3,              // corners held at their angles (rad²)
///       "pinned_traction": 0.01,           // Eq. 27, N² (needs pinned boundaries)
///       "compactness": {"weight": 1, "min_ratio": 0.1, "pair_stride": 1}
///     },
///     "max_iterations": 50,                 // L-BFGS iterations (default 50)
///     "time_limit": 0,                      // s of wall time per run (0: none)
///     "checkpoint_every": 5,                // iterations between checkpoints (default 5)
///     "min_area_ratio": 0.05,               // trial patterns with smaller triangles fail
///     "lbfgs": {"memory": 8, "gradient_tolerance": 0, "relative_gradient_tolerance": 1e-3,
///               "value_tolerance": 0,
///               "relative_decrease_tolerance": 1e-9, // progress over stall_iterations
///               "stall_iterations": 20,   //   below which the gradient is checked
///               "gradient_check_tolerance": 0.05,  // FD agreement of that check
///               "max_step": 0, "max_step_fraction": 0.5,  // trust radius
///               "max_compression": 0.5,   // no step shrinks a triangle below half
///               "snap_iterations": 3,     // after 3 iterations limited by a
///                                         // snap-through, jump through it (0: off)
///               "snap_jumps": 3,          // jumps per run; then stop there
///               "step_growth": 2,         // first trial moves no point more than 2x
///                                         // the previous iteration's farthest
///                                         // converged trial (0: off)
///               "armijo": 1e-4, "max_line_search": 30},
///     "remesh": {"enabled": true,          // remesh pieces whose rest mesh degrades:
///                "min_angle_deg": 10,      //   smallest angle below this (degrees),
///                "min_area_fraction": 0.1, //   a triangle below this × the equilateral
///                                          //   area of the target edge, or inverted
///                "edge_length": 0,         // target edge (m); 0: each piece's initial mean
///                "smoothing_iterations": 10}
///   }
///
/// Units of the terms (see each term's header): stretch and directional stretch m², shape m²,
/// pressure Pa²·m², seam traction N, sliding N², pinned traction N², seam length and boundary
/// spacing m², boundary smoothness 1/m, compactness dimensionless. Weights are >= 0; weight 0
/// switches a term off.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tightfit/body/skeleton_pose.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/body/skinning.hpp"
#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/objectives/pressure_region.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/resolution.hpp"

namespace tightfit {

struct StretchObjectiveSpec {
  double weight = 1.0;
  bool all_poses =
      false;  ///< "poses": "all": also in every scene pose (objectives/all_poses_term.hpp)
  double min_stretch = 1.0;
  std::optional<double> max_stretch;  ///< none: no upper bound
};

/// Stretch bounds on one fabric direction of every piece (DirectionalStretchObjective).
struct DirectionalStretchObjectiveSpec {
  StretchObjectiveSpec bounds;  ///< weight and stretch range
  bool across_grain = true;     ///< false: along the grain
};

struct ShapeObjectiveSpec {
  double weight = 1.0;
  std::filesystem::path target;  ///< target surface mesh (resolved against the scene folder)
  double radius = 0.01;          ///< IMLS kernel radius h (m)
  /// Leave the pinned boundary vertices (Garment::pinned) out of the sum: their place
  /// on the body is prescribed by the designer (paper Sec. 4.1, "Forces on Boundary"),
  /// so only the free garment is asked to follow the target.
  bool skip_pinned = false;
};

struct PressureObjectiveSpec {
  double weight = 1.0;
  bool all_poses = false;  ///< "poses": "all": also in every scene pose
  /// No range given: the targets are the scene's `"pressure": {"regions": [...]}`
  /// (copied into `regions` by read_optimization_scene). Else [min_pa, max_pa] on the
  /// whole garment.
  bool scene_regions = false;
  double min_pa = 0.0;                     ///< Pa (min_mmhg converted)
  double max_pa = 0.0;                     ///< Pa
  std::vector<PressureRegion> regions;     ///< when scene_regions
  std::string regions_source;              ///< the scene file, for errors about the regions
  std::shared_ptr<const SkinWeights> rig;  ///< skin weights of bone regions (may be null)
  double rig_radius = 0.03;                ///< m
};

struct SeamTractionObjectiveSpec {
  double weight = 1.0;
};

/// The scene's poses as the design terms need them (filled by read_optimization_scene
/// when a term asks for poses): the rig's skin weights, how they blend, and the bone
/// motions of every pose of the scene, by name, in scene order.
struct DesignPoses {
  std::shared_ptr<const SkinWeights> rig;
  SkinningMethod skinning = SkinningMethod::kDualQuaternion;
  std::vector<std::pair<std::string, std::map<std::string, RigidMotion>>> bone_motions;
  std::string source;  ///< the scene file, for errors about the poses
};

/// The sliding objective over the scene's poses (objectives/sliding_objective.hpp).
struct SlidingObjectiveSpec {
  double weight = 1.0;
  double friction = 0.3;           ///< Coulomb coefficient μ >= 0
  std::vector<std::string> poses;  ///< pose names; empty: every pose of the scene
};

struct RegularizerWeights {
  double seam_length = 0.0;
  double boundary_spacing = 0.0;
  double boundary_smoothness = 0.0;
  /// Corners held at their reference angles (design/regularizer_corner_angle.hpp).
  double corner_angle = 0.0;
  double compactness = 0.0;
  CompactnessOptions compactness_options;
  /// Eq. 27: the tangential force the pins hold (objectives/pinned_traction_regularizer.hpp).
  double pinned_traction = 0.0;
};

struct OptimizationSpec {
  std::optional<StretchObjectiveSpec> stretch;
  std::optional<DirectionalStretchObjectiveSpec> directional_stretch;
  std::optional<ShapeObjectiveSpec> shape;
  std::optional<PressureObjectiveSpec> pressure;
  std::optional<SeamTractionObjectiveSpec> seam_traction;
  std::optional<SlidingObjectiveSpec> sliding;
  DesignPoses poses;  ///< the scene's poses (empty unless a term uses them)
  RegularizerWeights regularizers;
  int checkpoint_every = 5;
  PatternOptimizerOptions optimizer;  ///< max_iterations default 50 here
  DesignProblemOptions problem;
  /// The resolution the terms' vertex and edge weights refer to (objectives/
  /// resolution.hpp): the design's initial mesh, so that the objective rebuilt after a
  /// remeshing measures the same; not read from the scene (unknown: each garment's own).
  ResolutionReference resolution;
};

/// Parses `section` (the value of "optimize") of scene `file`; `path` is its JSON
/// pointer, `base_dir` resolves the shape target. Throws InputError on any problem,
/// including a section that switches every term off.
OptimizationSpec parse_optimization_spec(const nlohmann::json& section, const std::string& file,
                                         const std::string& path,
                                         const std::filesystem::path& base_dir);

}  // namespace tightfit
