#pragma once
/// The scene file: one JSON document describing a body, a garment on it, the
/// materials and the solver settings. Its schema is `schema/scene.schema.json`; this
/// parser enforces it strictly (unknown keys and wrong types are InputErrors naming
/// the file and the JSON path). All values in SI units (m, Pa).
///
///   {
///     "body": { ...body spec, see body/body_spec.hpp... },
///     "garment": {"sleeve": {...}} | {"cover": {"scale": 0.9}}
///              | {"layout": {...garment/layout_spec.hpp...} | "layout.json",
///                 "pattern": {...garment/pattern_options.hpp...}},
///       a layout anchored on the skeleton (bones instead of points) takes the skeleton
///       and skin weights of the scene's "rig";
///     "fabric": {"youngs_modulus": 5.4e6, "poisson_ratio": 0.33, "thickness": 1e-4,
///                "regime_smoothing": 1e-3, "relaxation": 0}
///             | {"model": "measured", ...} | "fabric.json"   (scene/fabric_spec.hpp),
///       relaxation r in [0, 1): the share of its tension a knit loses with wear; every
///       simulation (and so every design) uses the worn fabric, E (1 − r) or the
///       unloading curves, so that pressure targets hold after relaxation (the new
///       garment presses about 1/(1 − r) times harder). materials.fabric holds the worn
///       fabric.
///     "seam": {"youngs_modulus": 0, "width": 0.005, "thickness": 2e-4},
///     "body_material": {"youngs_modulus": 24780, "poisson_ratio": 0.49, "rigid": false},
///     "solver": {"relative_force_tolerance": 1e-9, "max_iterations": 100,
///                "limit_level": 8},
///     "pressure": {"shape_operator": "mid_edge" | "limit_surface",
///                  "regions": [...design/pressure_region.hpp...],
///                  "rig": {"mesh": "body.obj", "weights": "default_weights.mhw",
///                          "radius": 0.03}},
///     "rig": {...}, "poses": [...],    // scene/poses.hpp
///     "measurements": [{"name": "calf", "point": {"bone": "lowerleg01.L", "at": 0.45},
///                       "normal": "along_bone"}]   // garment/measurement_levels.hpp
///     "patterns": {...}                // scene/pattern_export_spec.hpp
///   }
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/body/body_spec.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/garment/measurement_levels.hpp"
#include "tightfit/garment/pattern_options.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/objectives/pressure_region.hpp"
#include "tightfit/scene/pattern_export_spec.hpp"
#include "tightfit/scene/poses.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

/// How the garment is made.
enum class GarmentKind { kSleeve, kCover, kLayout };

struct GarmentSpec {
  GarmentKind kind = GarmentKind::kSleeve;
  SleeveParams sleeve;       ///< kind == kSleeve
  double cover_scale = 0.9;  ///< kind == kCover: rest size / body size
  LayoutSpec layout;         ///< kind == kLayout: panels, seams, pinned boundaries
  PatternOptions pattern;    ///< kind == kLayout: flattening, scale-down, meshing
  std::string json_path;     ///< JSON pointer of the garment section
};

struct SceneSpec {
  std::string file;                ///< the scene file (for messages)
  std::filesystem::path base_dir;  ///< relative paths resolve against this folder
  nlohmann::json document;         ///< the whole scene, for reports
  BodySpec body;
  GarmentSpec garment;
  SimulationMaterials materials;
  /// The fabric file the scene named ("fabric": "FILE", scene/fabric_spec.hpp), resolved;
  /// empty when the fabric is inline. `document` holds the file's object in its place.
  std::filesystem::path fabric_file;
  NewtonOptions newton;
  LimitSurfaceOptions limit;
  ShapeOperatorKind pressure_operator = ShapeOperatorKind::kMidEdge;
  /// Pressure targets by region: reported by every command that simulates, and the
  /// pressure objective's targets when it gives no range of its own.
  std::vector<PressureRegion> pressure_regions;
  /// The rig of bone regions ("pressure": {"rig": {...}}, design/pressure_region.hpp),
  /// loaded; null when the scene gives none.
  std::shared_ptr<const SkinWeights> pressure_rig;
  double pressure_rig_radius = 0.03;  ///< m
  /// The rig ("rig", scene/poses.hpp), loaded; null when the scene gives none. Bone
  /// pressure regions use it when "pressure" has no rig of its own.
  std::shared_ptr<const SceneRig> rig;
  /// The poses ("poses"), resolved to bone rotations of the rig's skeleton.
  std::vector<ScenePose> poses;
  /// The levels of the ease table listed in the scene ("measurements"; garment/
  /// measurement_levels.hpp). Without the key (`measurements_given` false) the outputs
  /// measure at the standard levels of `skeleton`, or by planes without one; an empty
  /// list turns the table off.
  std::vector<MeasurementLevel> measurements;
  bool measurements_given = false;
  /// The body's skeleton: the body's own "skeleton" (joints file), else the rig's; null
  /// without either. `skeleton_source` names it in messages.
  std::shared_ptr<const std::map<std::string, BoneSegment>> skeleton;
  std::string skeleton_source;
  /// The "patterns" section: how the pattern files are drawn (defaults when absent).
  PatternExportSpec patterns;
  /// The "optimize" section (objectives, regularizers, optimizer settings), validated by
  /// the design layer's parser when a command optimizes; null when absent.
  nlohmann::json optimize;
};

/// Reads and validates a scene file.
SceneSpec read_scene(const std::filesystem::path& file);
/// Validates a scene document; `file` names it in errors, `base_dir` resolves paths.
SceneSpec parse_scene(const nlohmann::json& document, const std::string& file,
                      const std::filesystem::path& base_dir);

}  // namespace tightfit
