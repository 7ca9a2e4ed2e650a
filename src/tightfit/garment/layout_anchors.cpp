#include "tightfit/garment/layout_anchors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/nearest_word.hpp"
#include "tightfit/geometry/plane_loops.hpp"

namespace tightfit {
namespace {

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

std::string format_vector(const Vec3& p) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

/// "; did you mean \"NAME\"?" for the known name nearest to `name`, or "".
template <class Map>
std::string suggestion(const std::string& name, const Map& known) {
  std::vector<std::string> names;
  for (const auto& entry : known) names.push_back(entry.first);
  const std::string near = nearest_word(name, names);
  return near.empty() ? "" : "; did you mean \"" + near + "\"?";
}

class Resolver {
 public:
  Resolver(const LayoutSpec& spec, const TriMesh& body, const LayoutRig& rig)
      : spec_(spec), body_(body), rig_(rig) {}

  /// Makes `plane` absolute and checks that it crosses the body. `what` names its kind.
  void resolve(LayoutPlane& plane, const std::string& what) {
    if (plane.anchor) {
      const BoneSegment& bone = find_bone(plane.anchor->bone, plane.source_path + "/point/bone");
      plane.point = anchor_point(bone, plane.anchor->at);
      plane.anchor.reset();
    }
    if (plane.along_bone) {
      const std::string path = plane.source_path + "/normal";
      find_bone(plane.along_bone->bone, path);  // a rig must be given
      plane.normal = resolve_bone_direction(*plane.along_bone, *rig_.skeleton, spec_.source, path,
                                            rig_.source);
      plane.along_bone.reset();
    }
    if (plane.is_field()) {
      if (plane.field.empty()) {
        plane.field = plane.local ? local_field(plane) : bone_field(plane);
      } else if (plane.field.size() != static_cast<std::size_t>(body_.num_vertices())) {
        throw std::invalid_argument("resolve_layout_anchors: plane \"" + plane.name +
                                    "\" was resolved on another body");
      }
    }
    check_crosses(plane, what);
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(spec_.source, path + ": " + what);
  }

  const BoneSegment& find_bone(const std::string& name, const std::string& path) const {
    if (rig_.skeleton == nullptr)
      fail(path, "bone \"" + name +
                     "\": the layout is anchored on the skeleton, but no skeleton "
                     "is given (the scene's \"rig\": {\"mesh\", \"weights\", \"joints\"})");
    return find_anchor_bone(*rig_.skeleton, name, spec_.source, path, rig_.source);
  }

  std::vector<double> bone_field(const LayoutPlane& plane) {
    const std::string path = plane.source_path + "/bones";
    if (rig_.weights == nullptr)
      fail(path, "bone region \"" + plane.name +
                     "\" needs skin weights, but none are given "
                     "(the scene's \"rig\": {\"mesh\", \"weights\", \"joints\"})");
    for (std::size_t i = 0; i < plane.bones.size(); ++i)
      if (!rig_.weights->bones.contains(plane.bones[i]))
        fail(path + "/" + std::to_string(i),
             "unknown bone \"" + plane.bones[i] + "\" (no skin weights for it in " +
                 rig_.weights->source + ")" + suggestion(plane.bones[i], rig_.weights->bones));
    if (!surface_weights_) surface_weights_ = transfer_skin_weights(*rig_.weights, body_.vertices);
    const VecX summed = surface_weights_->summed(plane.bones);
    std::vector<double> field(static_cast<std::size_t>(summed.size()));
    for (Eigen::Index v = 0; v < summed.size(); ++v)
      field[static_cast<std::size_t>(v)] = summed[v] - 0.5;
    return field;
  }

  /// The signed distance to the plane beyond its loop nearest to its point, its
  /// absolute value elsewhere.
  std::vector<double> local_field(const LayoutPlane& plane) const {
    std::vector<double> distance(static_cast<std::size_t>(body_.num_vertices()));
    for (int v = 0; v < body_.num_vertices(); ++v)
      distance[static_cast<std::size_t>(v)] = plane.distance(body_.vertices.row(v).transpose());
    BeyondLoop loop;
    try {
      loop = beyond_nearest_loop(body_, distance, plane.point, plane.normal, "");
    } catch (const InputError& e) {
      fail(plane.source_path, "local plane \"" + plane.name + "\": " + e.what());
    }
    for (std::size_t v = 0; v < distance.size(); ++v)
      distance[v] = loop.beyond[v] ? -std::abs(distance[v]) : std::abs(distance[v]);
    return distance;
  }

  void check_crosses(const LayoutPlane& plane, const std::string& what) const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int v = 0; v < body_.num_vertices(); ++v) {
      const double d = plane.is_field() ? plane.field[static_cast<std::size_t>(v)]
                                        : plane.distance(body_.vertices.row(v).transpose());
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    if (lo < 0.0 && hi > 0.0) return;
    const std::string name = what + " \"" + plane.name + "\" misses the body: ";
    if (plane.is_bone_region()) {
      std::string bones;
      for (const std::string& b : plane.bones) bones += (bones.empty() ? "" : ", ") + b;
      fail(plane.source_path,
           name + "the bones " + bones + " dominate " + (hi > 0.0 ? "all" : "no part") +
               " of the body surface (summed skin weight " + format_number(lo + 0.5) + " to " +
               format_number(hi + 0.5) + "; the region is where it is >= 1/2)");
    }
    if (body_.num_vertices() == 0) fail(plane.source_path, name + "the body surface is empty");
    fail(plane.source_path,
         name + "it does not cross the body surface, which lies on its " + (hi > 0.0 ? "+" : "-") +
             " side, " + format_number(std::min(std::abs(lo), std::abs(hi))) + " to " +
             format_number(std::max(std::abs(lo), std::abs(hi))) + " m from it (point " +
             format_vector(plane.point) + " m, normal " + format_vector(plane.normal) + ")");
  }

  const LayoutSpec& spec_;
  const TriMesh& body_;
  const LayoutRig& rig_;
  std::optional<PointWeights> surface_weights_;  ///< the body surface's weights, once needed
};

}  // namespace

LayoutSpec resolve_layout_anchors(const LayoutSpec& spec, const TriMesh& body_surface,
                                  const LayoutRig& rig) {
  LayoutSpec out = spec;
  Resolver resolver(spec, body_surface, rig);
  for (LayoutPlane& plane : out.region) resolver.resolve(plane, "region plane");
  for (LayoutPlane& plane : out.dividers) resolver.resolve(plane, "divider");
  for (PinRule& pin : out.pins)
    if (pin.kind == PinRule::Kind::kOnPlane)
      resolver.resolve(pin.plane, "the plane of pinned boundary");
  return out;
}

}  // namespace tightfit
