#include "tightfit/garment/layout_spec.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

namespace tightfit {
namespace {

/// "bones": [NAME, ...] of a bone region.
std::vector<std::string> parse_bone_list(JsonFields& f) {
  const nlohmann::json& bones = f.raw("bones");
  if (!bones.is_array() || bones.empty())
    f.fail("expected a non-empty array of bone names", "bones");
  std::vector<std::string> out;
  for (size_t i = 0; i < bones.size(); ++i) {
    const std::string where = "bones/" + std::to_string(i);
    if (!bones[i].is_string() || bones[i].get<std::string>().empty())
      f.fail("expected a bone name", where);
    const std::string name = bones[i].get<std::string>();
    if (std::find(out.begin(), out.end(), name) != out.end())
      f.fail("bone \"" + name + "\" listed twice", where);
    out.push_back(name);
  }
  return out;
}

/// A plane of "region" or "dividers" (`named`, bone regions allowed) or a pin's plane.
LayoutPlane parse_plane(JsonFields& f, bool named) {
  LayoutPlane plane;
  plane.source_path = f.path();
  if (named) plane.name = f.string("name");
  if (f.has("bones")) {
    if (!named)
      f.fail(
          "a pin's plane cannot be a bone region; pin on a bone region of \"region\" by its name",
          "bones");
    for (const char* key : {"point", "normal"})
      if (f.has(key))
        f.fail("not allowed in a bone region (it is cut where the bones' skin weight is 1/2)", key);
    plane.bones = parse_bone_list(f);
  } else {
    parse_anchored_point(f, "point", plane.point, plane.anchor);
    parse_anchored_direction(f, "normal", plane.anchor, plane.normal, plane.along_bone);
    if (named) plane.local = f.boolean("local", false);
  }
  f.finish();
  return plane;
}

std::vector<LayoutPlane> parse_planes(JsonFields& f, const std::string& key) {
  std::vector<LayoutPlane> planes;
  std::set<std::string> names;
  for (auto& pf : f.objects(key, false, kMaxSceneParts)) {
    planes.push_back(parse_plane(pf, true));
    if (planes.back().name.empty()) pf.fail("empty name", "name");
    if (!names.insert(planes.back().name).second)
      pf.fail("duplicate plane name \"" + planes.back().name + "\"", "name");
  }
  return planes;
}

int find_plane(const std::vector<LayoutPlane>& planes, const std::string& name) {
  for (size_t i = 0; i < planes.size(); ++i)
    if (planes[i].name == name) return static_cast<int>(i);
  return -1;
}

PanelRule parse_panel(JsonFields& f, const std::vector<LayoutPlane>& dividers) {
  PanelRule rule;
  rule.source_path = f.path();
  rule.name = f.string("name");
  if (rule.name.empty()) f.fail("empty name", "name");
  const auto& sides = f.raw("sides");
  if (!sides.is_null()) {
    if (!sides.is_array()) f.fail("expected an array of strings like \"+divider\"", "sides");
    std::set<int> used;
    for (size_t i = 0; i < sides.size(); ++i) {
      const std::string where = "sides/" + std::to_string(i);
      if (!sides[i].is_string()) f.fail("expected a string like \"+divider\"", where);
      const std::string s = sides[i].get<std::string>();
      if (s.size() < 2 || (s[0] != '+' && s[0] != '-'))
        f.fail("expected \"+name\" or \"-name\", got \"" + s + "\"", where);
      const int d = find_plane(dividers, s.substr(1));
      if (d < 0) f.fail("unknown divider \"" + s.substr(1) + "\"", where);
      if (!used.insert(d).second) f.fail("divider \"" + s.substr(1) + "\" listed twice", where);
      rule.sides.emplace_back(d, s[0] == '+' ? 1 : -1);
    }
  }
  f.finish();
  return rule;
}

LayoutOpening parse_opening(JsonFields& f) {
  LayoutOpening opening;
  opening.source_path = f.path();
  opening.name = f.string("name");
  if (opening.name.empty()) f.fail("empty name", "name");
  opening.center = f.vec3("center");
  const bool sphere = f.has("radius"), ellipsoid = f.has("radii");
  if (sphere == ellipsoid) f.fail("give exactly one of \"radius\" and \"radii\"");
  if (sphere) {
    opening.radii = Vec3::Constant(f.positive("radius"));
  } else {
    opening.radii = f.vec3("radii");
    if (!(opening.radii.minCoeff() > 0)) f.fail("every semi-axis must be positive (m)", "radii");
  }
  f.finish();
  return opening;
}

PinRule parse_pin(JsonFields& f, const LayoutSpec& spec) {
  PinRule pin;
  pin.source_path = f.path();
  pin.name = f.string("name");
  const bool on_plane = f.has("on_plane");
  const bool nearest = f.has("nearest");
  if (on_plane == nearest) f.fail("give exactly one of \"on_plane\" and \"nearest\"");
  if (nearest) {
    pin.kind = PinRule::Kind::kNearest;
    pin.point = f.vec3("nearest");
    pin.max_distance = f.positive("max_distance", std::numeric_limits<double>::infinity());
  } else {
    const auto& j = f.raw("on_plane");
    if (j.is_string()) {
      pin.kind = PinRule::Kind::kOnRegionPlane;
      const std::string name = j.get<std::string>();
      if (spec.is_mesh_layout())
        f.fail("a mesh layout has no region planes; give the plane as {\"point\", \"normal\"}",
               "on_plane");
      pin.region_plane = find_plane(spec.region, name);
      if (pin.region_plane < 0) f.fail("unknown region plane \"" + name + "\"", "on_plane");
    } else if (j.is_object()) {
      pin.kind = PinRule::Kind::kOnPlane;
      JsonFields pf(j, f.source(), f.child_path("on_plane"));
      pin.plane = parse_plane(pf, false);
      pin.plane.name = pin.name;
    } else {
      f.fail("expected a region plane name or {\"point\", \"normal\"}", "on_plane");
    }
  }
  f.finish();
  return pin;
}

}  // namespace

LayoutSpec parse_layout_spec(JsonFields& f, const std::string& base_dir) {
  LayoutSpec spec;
  spec.source = f.source();
  spec.path = f.path();
  f.string("description", std::string());
  if (f.has("mesh")) {
    const std::string mesh = f.string("mesh");
    if (mesh.empty()) f.fail("empty file name", "mesh");
    std::filesystem::path p(mesh);
    if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
    spec.mesh_file = p.string();
    for (const char* key : {"region", "dividers", "panels", "openings"})
      if (f.has(key)) f.fail("not allowed together with \"mesh\"", key);
    spec.weld_tolerance = f.positive("weld_tolerance", spec.weld_tolerance, true);
  } else {
    spec.region = parse_planes(f, "region");
    spec.dividers = parse_planes(f, "dividers");
    for (const auto& d : spec.dividers)
      if (find_plane(spec.region, d.name) >= 0)
        throw InputError(spec.source,
                         d.source_path + ": name \"" + d.name + "\" is also a region plane");
    std::set<std::string> names;
    for (auto& pf : f.objects("panels", true, kMaxSceneParts)) {
      spec.panels.push_back(parse_panel(pf, spec.dividers));
      if (!names.insert(spec.panels.back().name).second)
        pf.fail("duplicate panel name \"" + spec.panels.back().name + "\"", "name");
    }
    if (spec.panels.empty()) f.fail("at least one panel is needed", "panels");
    std::set<std::string> opening_names;
    for (auto& of : f.objects("openings", false, kMaxSceneParts)) {
      spec.openings.push_back(parse_opening(of));
      if (!opening_names.insert(spec.openings.back().name).second)
        of.fail("duplicate opening name \"" + spec.openings.back().name + "\"", "name");
    }
  }
  std::set<std::string> pin_names;
  for (auto& pf : f.objects("pinned", false, kMaxSceneParts)) {
    spec.pins.push_back(parse_pin(pf, spec));
    if (!pin_names.insert(spec.pins.back().name).second)
      pf.fail("duplicate pin name \"" + spec.pins.back().name + "\"", "name");
  }
  spec.seam_tolerance = f.positive("seam_tolerance", spec.seam_tolerance);
  spec.area_tolerance = f.positive("area_tolerance", spec.area_tolerance);
  spec.stray_part_fraction = f.positive("stray_part_fraction", spec.stray_part_fraction, true);
  if (spec.stray_part_fraction >= 0.5)
    f.fail("must be below 0.5 (a share of the panel's area)", "stray_part_fraction");
  spec.plane_tolerance = f.positive("plane_tolerance", spec.plane_tolerance);
  f.finish();
  return spec;
}

std::string LayoutSpec::first_rig_use() const {
  for (const std::vector<LayoutPlane>* planes : {&region, &dividers})
    for (const LayoutPlane& plane : *planes)
      if (plane.needs_rig()) return plane.source_path;
  for (const PinRule& pin : pins)
    if (pin.kind == PinRule::Kind::kOnPlane && pin.plane.needs_rig()) return pin.plane.source_path;
  return {};
}

LayoutSpec read_layout_spec(const std::string& file) {
  const nlohmann::json j = read_json_file(file);
  JsonFields f(j, file, "");
  return parse_layout_spec(f, std::filesystem::path(file).parent_path().string());
}

}  // namespace tightfit
