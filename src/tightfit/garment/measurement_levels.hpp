#pragma once
/// Where the ease table (garment/ease_table.hpp) measures: levels listed in the scene,
/// the standard levels of the MakeHuman skeleton, or planes across the garment.
///
/// The scene's list ("measurements"), one object per level:
///
///   {"name": "calf", "point": [x, y, z] | {"bone": "lowerleg01.L", "at": 0.45},
///    "normal": [x, y, z] | "up" | "along_bone" | … }   // body/skeleton_anchor.hpp
///
/// The standard levels follow the measuring points of compression hosiery (RAL-GZ 387:
/// cB ankle, cC calf, cD below the knee, cE knee, cF mid-thigh, cG upper thigh) and the
/// girths of the garment trade (neck, chest, waist, hip; bicep, elbow, forearm, wrist):
/// each a plane through a point at a fraction along a bone of the MakeHuman skeleton,
/// normal to the bone (table in measurement_levels.cpp; the fractions are tightfit's
/// choice for the MakeHuman rig, about where a tape measure goes).
#include <map>
#include <string>
#include <vector>

#include "tightfit/body/body_spec.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/garment/ease_table.hpp"

namespace tightfit {

/// Parses the array `f[key]` of levels (origin "scene"). Points and normals anchored on
/// bones are resolved on `skeleton`; InputError (the file and the JSON path) for a bad
/// entry, a duplicate name, an unknown bone, or bones without a skeleton.
std::vector<MeasurementLevel> parse_measurement_levels(JsonFields& f, const std::string& key,
                                                       const SkeletonRef& skeleton);

/// The standard levels whose bones `skeleton` has (origin "skeleton"), limbs on both
/// sides ("calf.L", "calf.R": the body's left and right, as the bones are named).
/// Empty for a skeleton without MakeHuman bone names.
std::vector<MeasurementLevel> skeleton_levels(const std::map<std::string, BoneSegment>& skeleton);

/// Levels by planes (origin "planes"), for a body without a skeleton: planes normal to
/// `up` (unit) at every multiple of `spacing` (m) of the height along `up` within the
/// extent of `garment` (the fitted garment mesh, m); one level per closed loop of the
/// garment's cut at that height, through the centroid of the loop's crossing points.
/// Named by the height: "y 0.35 m" for an up direction along a coordinate axis
/// ("height 0.35 m" otherwise), with the loop's centroid along the first axis across
/// appended when a height has several loops: "y 0.35 m (x +0.09 m)".
std::vector<MeasurementLevel> plane_levels(const TriMesh& garment, const Vec3& up, double spacing);

}  // namespace tightfit
