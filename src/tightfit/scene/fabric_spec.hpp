#pragma once
/// The scene's "fabric": the isotropic relaxed StVK knit (the default) or a knit measured
/// by strip tests (physics/fabric_law.hpp), inline or in a file of its own.
///
///   "fabric": {"youngs_modulus": 5.4e6, "poisson_ratio": 0.33, "thickness": 1e-4,
///              "regime_smoothing": 1e-3, "relaxation": 0}
///   "fabric": {"model": "measured", "name": "power-net 78/22", "thickness": 0.0005,
///              "source": "where the curves come from",
///              "wale":   {"strain": [0, 0.2, 0.5, 1.0], "tension_n_per_m": [0, 40, 130, 420]},
///              "course": {"strain": [...], "tension_n_per_m": [...]},
///              "coupling": 0.0, "shear_n_per_m": 30 | "bias": {curve at 45°},
///              "unloading": {"wale": {curve}, "course": {curve}} | "relaxation": 0.2}
///   "fabric": "fabrics/power_net.json"     (relative to the scene file; same shape)
///
/// Hysteresis: the worn garment sits on the unloading curves. `relaxation` r is the
/// special case of unloading curves that are the loading ones scaled by (1 − r) (for the
/// isotropic model: E (1 − r)); a fabric gives one or the other, not both.
///
/// Shear from a bias curve: a strip cut at 45° to the grain is a series of the course,
/// wale and shear compliances; with the curves' initial stiffnesses k (N/m) and the
/// coupling κ = c √(k_c k_w) (fabric_law.hpp),
///   1/k_45 = (k_c + k_w − 2κ) / (4 (k_c k_w − κ²)) + 1/(4 G),
/// which gives G from the bias curve's initial stiffness k_45.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"

namespace tightfit {

/// The fabric of a scene: the material the physics uses and the relaxation the user gave
/// (result.json and pattern labels report the new fabric as well as the worn one).
struct FabricSpec {
  ClothMaterial material;   ///< the worn fabric (isotropic E scaled, or the measured law)
  double relaxation = 0.0;  ///< r in [0, 1)
  /// The fabric file the scene named ("" when inline), resolved against the scene folder.
  std::filesystem::path file;
  nlohmann::json document;  ///< the fabric's JSON object (inline or the file's)
};

/// Reads the scene member `value` at JSON path `json_path` of `scene_file`: an object, or
/// the path of a fabric file relative to `base_dir`. `defaults` gives the values of keys
/// not given. Throws InputError naming the scene (or the fabric file) and the JSON path.
FabricSpec parse_fabric_spec(const nlohmann::json& value, const std::string& scene_file,
                             const std::string& json_path, const std::filesystem::path& base_dir,
                             const ClothMaterial& defaults = {});

/// Reads a fabric file (the object form above). Throws InputError naming the file.
FabricSpec read_fabric_file(const std::filesystem::path& file, const ClothMaterial& defaults = {});

/// The shear stiffness G (N/m) that makes a strip cut at 45° as stiff as `bias_stiffness`
/// (N/m), given the course and wale initial stiffnesses and the coupling c (formula above).
/// Returns a value <= 0 when the bias strip is stiffer than the other three allow.
double shear_from_bias(double course_stiffness, double wale_stiffness, double coupling,
                       double bias_stiffness);

}  // namespace tightfit
