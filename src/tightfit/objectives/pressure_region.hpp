#pragma once
/// A pressure target of a compression garment: where on the garment it applies and its
/// range (the data; objectives/pressure_regions.hpp resolves it on a garment and gives
/// the membership weights). Read from the scene's `"pressure": {"regions": [...]}`:
///
///   {"name": "ankle",                            // required, unique
///    "pieces": ["left_leg", "right_leg"],        // optional: only these pattern pieces
///    "bones": ["lowerleg01.L", "lowerleg02.L"],  // optional: where these bones' summed
///                                                 //   skin weight is high (needs the
///                                                 //   scene's "pressure": {"rig": ...})
///    "above": {"point": [0, 0.08, 0], "normal": [0, 1, 0]},  // optional band planes: keep
///    "below": {"point": [0, 0.16, 0], "normal": [0, 1, 0]},  //   the side the normal of
///                                                 //   "above" points to, the other of "below"
///    "transition": 0.01,                          // m, width of the smooth step (default 0.01)
///    "min_mmhg": 23, "max_mmhg": 32}              // or "min_pa"/"max_pa" (Pa)
///
/// A region without pieces, bones and planes is the whole garment.
///
/// The rig (for bone regions): `"pressure": {"rig": {"mesh": "mh_male_regular.obj",
/// "weights": "default_weights.mhw", "radius": 0.03}}` — a mesh in the body's frame whose
/// vertex order the weights file uses (body/skin_weights.hpp) and the radius (m) of the
/// smooth interpolation of the weights to the garment (objectives/point_field.hpp).
#include <optional>
#include <string>
#include <vector>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A plane through `point` (m) with `normal` (unit after validation).
struct RegionPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
};

/// One pressure target: where it applies and its range (Pa).
struct PressureRegion {
  std::string name;
  std::vector<std::string> pieces;   ///< pattern piece names; empty: every piece
  std::vector<std::string> bones;    ///< rig bones whose summed skin weight selects; empty: none
  std::optional<RegionPlane> above;  ///< keep the side the plane's normal points to
  std::optional<RegionPlane> below;  ///< keep the side opposite to the plane's normal
  double transition = 0.01;          ///< width δ of the smooth step across a plane (m), >= 0
  double min_pa = 0.0;               ///< Pa
  double max_pa = 0.0;               ///< Pa, >= min_pa
};

/// Reads a pressure range given as "min_pa"/"max_pa" or "min_mmhg"/"max_mmhg" (exactly
/// one pair) from `f` into (min_pa, max_pa). Throws InputError for both or neither pair
/// or max < min.
void parse_pressure_range(JsonFields& f, double& min_pa, double& max_pa);

/// Reads one region object (above). Throws InputError naming the file and JSON path.
PressureRegion parse_pressure_region(JsonFields f);

/// The rig files of bone regions, resolved against the scene folder.
struct PressureRigSpec {
  std::string mesh;      ///< path of the rig mesh
  std::string weights;   ///< path of the skin weights file
  double radius = 0.03;  ///< m, interpolation radius of the weights
};

}  // namespace tightfit
