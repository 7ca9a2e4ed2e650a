#pragma once
/// Points and directions given on the skeleton instead of in absolute coordinates, so
/// that one spec fits every body of a rig (layout planes, body crops). The JSON forms:
///
/// * a point: `[x, y, z]` (m), or `{"bone": NAME, "at": t}`: head + t (tail − head) of
///   the bone, 0 ≤ t ≤ 1;
/// * a direction: `[x, y, z]`; a body axis `"left"` (+x), `"right"`, `"up"` (+y),
///   `"down"`, `"front"` (+z), `"back"`; `"along_bone"` / `"-along_bone"`: head → tail
///   of the point's bone (or tail → head); `{"along_bone": NAME, "reversed": false}`: of
///   another bone; `{"across_bones": [A, B], "reversed": false}`: normal to both bones,
///   d_A × d_B normalized (the plane of a bent limb).
#include <map>
#include <optional>
#include <string>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A point on a bone of the body's skeleton: head + at (tail − head).
struct BoneAnchor {
  std::string bone;
  double at = 0.0;  ///< fraction from the head (0) to the tail (1)
};

/// A direction along a bone of the body's skeleton: sign (tail − head) / |tail − head|;
/// or, with `across` set, the unit normal of the plane of two bones (a bent elbow):
/// sign (d_bone × d_across) / |d_bone × d_across|.
struct BoneDirection {
  std::string bone;
  double sign = 1.0;   ///< +1 or −1
  std::string across;  ///< the second bone of a cross product; empty: along `bone`
};

/// Parses `f[key]` as a point: sets `point` (m) for [x, y, z], or `anchor` for a bone
/// anchor (then `point` is left for the resolution). InputError naming the JSON path.
void parse_anchored_point(JsonFields& f, const std::string& key, Vec3& point,
                          std::optional<BoneAnchor>& anchor);

/// Parses `f[key]` as a direction: sets `direction` (unit) for a vector or a body axis,
/// or `along_bone` for a bone direction; `"along_bone"` needs `point_anchor` (the bone
/// of the point). InputError naming the JSON path.
void parse_anchored_direction(JsonFields& f, const std::string& key,
                              const std::optional<BoneAnchor>& point_anchor, Vec3& direction,
                              std::optional<BoneDirection>& along_bone);

/// The bone `name` of `skeleton`; InputError(source, path + ": …") for an unknown bone,
/// with the nearest known name when one is close. `skeleton_source` names the joints
/// file in the message.
const BoneSegment& find_anchor_bone(const std::map<std::string, BoneSegment>& skeleton,
                                    const std::string& name, const std::string& source,
                                    const std::string& path, const std::string& skeleton_source);

/// head + at (tail − head) of `bone` (m).
Vec3 anchor_point(const BoneSegment& bone, double at);

/// The unit direction `direction` names on `skeleton`. InputError(source, path + ": …")
/// for an unknown bone, a bone of zero length, or two parallel bones.
Vec3 resolve_bone_direction(const BoneDirection& direction,
                            const std::map<std::string, BoneSegment>& skeleton,
                            const std::string& source, const std::string& path,
                            const std::string& skeleton_source);

}  // namespace tightfit
