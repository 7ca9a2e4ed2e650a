#include "tightfit/garment/measurement_levels.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>

#include "tightfit/body/skeleton_anchor.hpp"
#include "tightfit/geometry/plane_loops.hpp"

namespace tightfit {
namespace {

/// A standard level: `name` at `at` along `bone` (a fraction of the bone from head to
/// tail; below 0: before the head), normal along the bone, or up (+y, the body frame)
/// when `horizontal`. Limb bones end in ".L"; the ".R" level mirrors it.
struct StandardLevel {
  const char* name;
  const char* bone;
  double at;
  bool horizontal;
};

// Legs after RAL-GZ 387 (cB ankle, cC calf, cD below knee, cE knee, cF mid-thigh,
// cG upper thigh); torso girths horizontal, as a tape measure goes on a standing body.
constexpr StandardLevel kStandardLevels[] = {
    {"neck", "neck02", 0.5, false},
    {"chest", "spine01", 0.0, true},
    {"waist", "spine03", 0.5, true},
    {"hip", "spine05", -0.5, true},  // below the pelvis' top: the seat
    {"thigh", "upperleg02.L", 0.2, false},
    {"mid-thigh", "upperleg02.L", 0.5, false},
    {"knee", "lowerleg01.L", 0.0, false},
    {"below-knee", "lowerleg01.L", 0.15, false},
    {"calf", "lowerleg01.L", 0.45, false},
    {"ankle", "lowerleg02.L", 0.8, false},
    {"bicep", "upperarm02.L", 0.4, false},
    {"elbow", "lowerarm01.L", 0.0, false},
    {"forearm", "lowerarm01.L", 0.4, false},
    {"wrist", "lowerarm02.L", 0.9, false},
};

std::string number_text(const char* format, double value) {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

/// `value` (m) with two decimals and its sign, "+0.00" for a value that rounds to zero.
std::string signed_metres(double value) {
  double rounded = std::round(value * 100.0) / 100.0;
  if (rounded == 0.0) rounded = 0.0;  // no "-0.00"
  return number_text("%+.2f", rounded);
}

/// "x", "y" or "z" when `axis` lies along a coordinate axis, else "".
std::string axis_name(const Vec3& axis) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(axis[k]) - 1.0) < 1e-9) return std::string(1, static_cast<char>('x' + k));
  return "";
}

}  // namespace

std::vector<MeasurementLevel> parse_measurement_levels(JsonFields& f, const std::string& key,
                                                       const SkeletonRef& skeleton) {
  std::vector<MeasurementLevel> levels;
  std::set<std::string> names;
  if (f.raw(key).is_null()) f.fail("expected an array of objects, got null", key);
  for (JsonFields& entry : f.objects(key)) {
    MeasurementLevel level;
    level.origin = "scene";
    level.name = entry.string("name");
    if (level.name.empty()) entry.fail("expected a name", "name");
    if (!names.insert(level.name).second)
      entry.fail("a second level named \"" + level.name + "\"", "name");
    std::optional<BoneAnchor> anchor;
    std::optional<BoneDirection> along_bone;
    parse_anchored_point(entry, "point", level.point, anchor);
    parse_anchored_direction(entry, "normal", anchor, level.normal, along_bone);
    entry.finish();
    if ((anchor || along_bone) && skeleton.bones == nullptr)
      entry.fail(
          "anchored on the skeleton, but there is none: give the body a \"skeleton\" (a joints "
          "file) or the scene a \"rig\"");
    if (anchor) {
      const std::string path = entry.child_path("point") + "/bone";
      level.point = anchor_point(
          find_anchor_bone(*skeleton.bones, anchor->bone, entry.source(), path, skeleton.source),
          anchor->at);
      level.anchor = anchor->bone + " at " + number_text("%g", anchor->at);
    } else {
      level.anchor = "point";
    }
    if (along_bone)
      level.normal = resolve_bone_direction(*along_bone, *skeleton.bones, entry.source(),
                                            entry.child_path("normal"), skeleton.source);
    if (!(level.normal.norm() > 0.0)) entry.fail("the normal must not be zero", "normal");
    level.normal.normalize();
    levels.push_back(std::move(level));
  }
  return levels;
}

std::vector<MeasurementLevel> skeleton_levels(const std::map<std::string, BoneSegment>& skeleton) {
  std::vector<MeasurementLevel> levels;
  for (const StandardLevel& s : kStandardLevels) {
    std::string bone = s.bone;
    const bool limb = bone.size() > 2 && bone.ends_with(".L");
    for (const char* side : {".L", ".R"}) {
      if (limb) bone.replace(bone.size() - 2, 2, side);
      const auto it = skeleton.find(bone);
      if (it != skeleton.end()) {
        const Vec3 d = it->second.tail - it->second.head;
        if (s.horizontal || d.norm() > 1e-9) {
          MeasurementLevel level;
          level.name = limb ? std::string(s.name) + side : std::string(s.name);
          level.origin = "skeleton";
          level.anchor = bone + " at " + number_text("%g", s.at);
          level.point = anchor_point(it->second, s.at);
          level.normal = s.horizontal ? Vec3(Vec3::UnitY()) : Vec3(d.normalized());
          levels.push_back(std::move(level));
        }
      }
      if (!limb) break;
    }
  }
  return levels;
}

std::vector<MeasurementLevel> plane_levels(const TriMesh& garment, const Vec3& up, double spacing) {
  std::vector<MeasurementLevel> levels;
  if (garment.num_vertices() == 0 || !(spacing > 0.0)) return levels;
  const Vec3 n = up.normalized();
  const VecX height = garment.vertices * n;
  const std::string axis = axis_name(n);
  const std::string prefix = axis.empty() ? "height" : (n[axis[0] - 'x'] < 0.0 ? "-" + axis : axis);
  // The first body axis across `up`, to tell loops of one height apart.
  int across = 0;
  for (int k = 0; k < 3; ++k)
    if (std::abs(n[k]) < 0.5) {
      across = k;
      break;
    }
  const auto first = static_cast<long>(std::ceil(height.minCoeff() / spacing));
  const auto last = static_cast<long>(std::floor(height.maxCoeff() / spacing));
  for (long k = first; k <= last; ++k) {
    const double h = static_cast<double>(k) * spacing;
    std::vector<double> side(static_cast<size_t>(garment.num_vertices()));
    for (int i = 0; i < garment.num_vertices(); ++i) side[static_cast<size_t>(i)] = height[i] - h;
    const PlaneCut cut = cut_by_plane(garment, side);
    std::vector<Vec3> centroid(static_cast<size_t>(cut.num_loops), Vec3::Zero());
    std::vector<int> count(static_cast<size_t>(cut.num_loops), 0);
    for (size_t i = 0; i < cut.edges.size(); ++i) {
      centroid[static_cast<size_t>(cut.loop[i])] +=
          crossing_point(garment, cut, static_cast<int>(i));
      ++count[static_cast<size_t>(cut.loop[i])];
    }
    int closed = 0;
    for (int l = 0; l < cut.num_loops; ++l) closed += cut.closed[static_cast<size_t>(l)];
    std::string name = prefix + " " + number_text("%.2f", h) + " m";
    for (int l = 0; l < cut.num_loops; ++l) {
      if (!cut.closed[static_cast<size_t>(l)]) continue;
      MeasurementLevel level;
      level.origin = "planes";
      level.point = centroid[static_cast<size_t>(l)] / count[static_cast<size_t>(l)];
      level.normal = n;
      level.anchor = name;
      level.name = name;
      if (closed > 1) {
        level.name += " (";
        level.name += std::string(1, static_cast<char>('x' + across));
        level.name += " ";
        level.name += signed_metres(level.point[across]);
        level.name += " m)";
      }
      levels.push_back(std::move(level));
    }
  }
  return levels;
}

}  // namespace tightfit
