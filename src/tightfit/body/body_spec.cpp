#include "tightfit/body/body_spec.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "tightfit/body/loop_limit.hpp"
#include "tightfit/body/scan_import.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/skeleton_anchor.hpp"
#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/mesh_budget.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit {
namespace {

constexpr double kDefaultMeshEdge = 0.015;
constexpr double kDefaultSoftTissue = 0.015;

std::string where(const JsonFields& f, const std::string& key = "") {
  return key.empty() ? (f.path().empty() ? "/" : f.path()) : f.child_path(key);
}

Vec3 nonzero_vec3(JsonFields& f, const std::string& key, const Vec3& fallback) {
  const Vec3 v = f.vec3(key, fallback);
  if (!(v.norm() > 0.0)) f.fail("expected a non-zero vector", key);
  return v;
}

std::string format_length(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

/// A generated body larger than any body part: the lengths were given in millimetres.
void check_body_size(JsonFields& f, double radius, double length) {
  constexpr double kLargestRadius = 2.0, kLargestLength = 5.0;  // m
  if (radius > kLargestRadius)
    f.fail("a radius of " + format_length(radius) +
               " m is larger than any body part: lengths are in metres "
               "(50 mm is 0.05)",
           "radius");
  if (length > kLargestLength)
    f.fail("a length of " + format_length(length) +
               " m is longer than any body: lengths are in metres "
               "(300 mm is 0.3)",
           "length");
}

void parse_cylinder(JsonFields& f, BodySpec& spec) {
  CylinderParams& c = spec.cylinder;
  c.radius = f.positive("radius");
  c.length = f.positive("length", std::nullopt, /*allow_zero=*/true);
  c.caps = f.choice("caps", {"round", "flat"}, std::string("round")) == "flat" ? CapStyle::kFlat
                                                                               : CapStyle::kRound;
  if (c.caps == CapStyle::kFlat && c.length == 0.0)
    f.fail("a cylinder with flat caps needs a positive length", "length");
  c.center = f.vec3("center", Vec3::Zero());
  c.axis = nonzero_vec3(f, "axis", Vec3::UnitZ());
  c.fit_limit = f.boolean("fit_limit", true);
  c.edge_length = f.positive("edge_length", default_generator_edge_length(c.radius));
  if (c.edge_length > c.radius) f.fail("the edge length must not exceed the radius", "edge_length");
  spec.edge_length = c.edge_length;
  check_body_size(f, c.radius, c.length);
  const double area = cylinder_area(c);
  if (const std::string problem = mesh_budget_problem(area, c.edge_length, "cylinder's surface");
      !problem.empty())
    f.fail(problem, "edge_length");
}

void parse_sphere(JsonFields& f, BodySpec& spec) {
  SphereParams& s = spec.sphere;
  s.radius = f.positive("radius");
  s.center = f.vec3("center", Vec3::Zero());
  s.fit_limit = f.boolean("fit_limit", true);
  s.edge_length = f.positive("edge_length", default_generator_edge_length(s.radius));
  if (s.edge_length > s.radius) f.fail("the edge length must not exceed the radius", "edge_length");
  spec.edge_length = s.edge_length;
  check_body_size(f, s.radius, 0.0);
  const double area = sphere_area(s);
  if (const std::string problem = mesh_budget_problem(area, s.edge_length, "sphere's surface");
      !problem.empty())
    f.fail(problem, "edge_length");
}

void parse_mesh(JsonFields& f, BodySpec& spec, const std::filesystem::path& base_dir,
                const SkeletonRef& rig) {
  MeshImport& m = spec.mesh;
  const std::string file = f.string("mesh");
  if (file.empty()) f.fail("expected a file name", "mesh");
  m.path =
      std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base_dir / file;
  m.scale_given = f.has("scale");
  m.scale = f.positive("scale", 1.0);
  if (f.has("units")) {
    const std::string units = f.choice("units", {"m", "cm", "mm"});
    m.units = metres_per_unit(units, f.source());
  }
  std::map<std::string, BoneSegment> own_skeleton;
  SkeletonRef skeleton = rig;
  if (f.has("skeleton")) {
    const std::filesystem::path joints = base_dir / f.string("skeleton");
    own_skeleton = read_skeleton(joints);
    skeleton = {&own_skeleton, joints.string()};
  }
  for (JsonFields& plane : f.objects("crop", false, kMaxSceneParts)) {
    CropPlane p;
    std::optional<BoneAnchor> anchor;
    std::optional<BoneDirection> along_bone;
    parse_anchored_point(plane, "point", p.point, anchor);
    parse_anchored_direction(plane, "normal", anchor, p.normal, along_bone);
    p.local = plane.boolean("local", false);
    if ((anchor || along_bone) && skeleton.bones == nullptr)
      plane.fail(
          "anchored on the skeleton, but there is none: give the body a \"skeleton\" "
          "(a joints file) or the scene a \"rig\"");
    if (anchor)
      p.point = anchor_point(find_anchor_bone(*skeleton.bones, anchor->bone, plane.source(),
                                              plane.child_path("point") + "/bone", skeleton.source),
                             anchor->at);
    if (along_bone) {
      const std::string path = plane.child_path("normal");
      p.normal = resolve_bone_direction(*along_bone, *skeleton.bones, plane.source(), path,
                                        skeleton.source);
    }
    plane.finish();
    m.crop.push_back(p);
  }
  m.remesh = f.boolean("remesh", true);
  m.remesh_options.iterations = f.integer("remesh_iterations", 5);
  if (m.remesh_options.iterations < 1) f.fail("expected at least 1", "remesh_iterations");
  m.remesh_options.sharp_angle_deg = f.number("sharp_angle_deg", 60.0);
  if (!(m.remesh_options.sharp_angle_deg > 0.0 && m.remesh_options.sharp_angle_deg <= 180.0))
    f.fail("expected an angle in (0, 180] degrees", "sharp_angle_deg");
  m.fit_limit = f.boolean("fit_limit", false);
  spec.edge_length = f.positive("edge_length", kDefaultMeshEdge);
  m.remesh_options.edge_length = spec.edge_length;
  m.remesh_options.min_feature_loop_length = 4.0 * spec.edge_length;
  m.remesh_options.cap_planes = m.crop;
}

void parse_core(JsonFields& f, BodySpec& spec, const std::filesystem::path& base_dir) {
  CoreOptions& core = spec.volume.core;
  const std::string path = spec.json_path + "/core";
  core.source = (f.source().empty() ? "" : f.source() + ": ") + path;
  auto object = f.object("core");
  if (!object) {
    core.soft_tissue = kDefaultSoftTissue;
    return;
  }
  JsonFields& c = *object;
  const bool has_skeleton = c.has("skeleton"), has_bones = c.has("bones");
  if (has_skeleton != has_bones) c.fail("\"skeleton\" and \"bones\" go together");
  const bool has_radius = c.has("radius");
  if (c.has("soft_tissue") || (!has_bones && !has_radius))
    core.soft_tissue = c.positive("soft_tissue", kDefaultSoftTissue);
  if (has_radius) {
    if (spec.source == BodySource::kMesh)
      c.fail("an embedded core radius needs a generator body", "radius");
    const double radius = c.positive("radius");
    try {
      core.embedded_core = spec.source == BodySource::kCylinder
                               ? cylinder_surface(cylinder_core(spec.cylinder, radius))
                               : sphere_surface(sphere_core(spec.sphere, radius));
    } catch (const std::invalid_argument& e) {
      c.fail(e.what(), "radius");
    }
  }
  if (has_bones) {
    const std::string file = c.string("skeleton");
    const std::filesystem::path skeleton_path =
        std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base_dir / file;
    const auto skeleton = read_skeleton(skeleton_path);
    const nlohmann::json& bones = c.raw("bones");
    if (!bones.is_array() || bones.empty())
      c.fail("expected a non-empty array of bone names", "bones");
    std::vector<std::string> names;
    for (size_t i = 0; i < bones.size(); ++i) {
      const std::string item = c.child_path("bones") + "/" + std::to_string(i);
      if (!bones[i].is_string()) throw InputError(c.source(), item + ": expected a bone name");
      names.push_back(bones[i].get<std::string>());
      if (!skeleton.count(names.back()))
        throw InputError(c.source(),
                         item + ": no bone \"" + names.back() + "\" in " + skeleton_path.string());
    }
    core.bones = select_bones(skeleton, names, where(c, "bones"));
  }
  core.bone_radius = c.positive("bone_radius", 0.01, /*allow_zero=*/true);
  c.finish();
}

BodySpec parse_fields(JsonFields& f, const std::filesystem::path& base_dir,
                      const SkeletonRef& rig) {
  BodySpec spec;
  spec.source_file = f.source();
  spec.json_path = f.path();
  const bool has_generator = f.has("generator"), has_mesh = f.has("mesh");
  if (has_generator == has_mesh) f.fail("expected exactly one of \"generator\" and \"mesh\"");
  if (has_generator) {
    const std::string kind = f.choice("generator", {"cylinder", "sphere"});
    spec.source = kind == "cylinder" ? BodySource::kCylinder : BodySource::kSphere;
    if (spec.source == BodySource::kCylinder)
      parse_cylinder(f, spec);
    else
      parse_sphere(f, spec);
  } else {
    spec.source = BodySource::kMesh;
    parse_mesh(f, spec, base_dir, rig);
  }
  const VolumeOptions defaults = default_volume_options(spec.edge_length);
  spec.volume = defaults;
  spec.volume.quality.max_radius_edge =
      f.positive("max_radius_edge", defaults.quality.max_radius_edge);
  if (spec.volume.quality.max_radius_edge < 1.0) f.fail("expected a value ≥ 1", "max_radius_edge");
  spec.volume.quality.min_dihedral_deg =
      f.number("min_dihedral_deg", defaults.quality.min_dihedral_deg);
  if (!(spec.volume.quality.min_dihedral_deg >= 0.0 &&
        spec.volume.quality.min_dihedral_deg <= 18.0))
    f.fail("expected an angle in [0, 18] degrees", "min_dihedral_deg");
  const double interior = f.positive("interior_edge_length", 2.0 * spec.edge_length);
  spec.volume.quality.max_volume = regular_tet_volume(interior);
  spec.volume.core.soft_tissue.reset();
  parse_core(f, spec, base_dir);
  f.finish();
  return spec;
}

/// The message of an InputError without its source prefix.
std::string message_of(const InputError& e) {
  const std::string what = e.what();
  const std::string prefix = e.source() + ": ";
  return !e.source().empty() && what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

/// Error location "FILE: /json/path" of a member of the spec.
std::string spec_location(const BodySpec& spec, const std::string& member) {
  const std::string path = spec.json_path + member;
  return (spec.source_file.empty() ? "" : spec.source_file + ": ") + (path.empty() ? "/" : path);
}

void fit_limit_to(TriMesh& surface, const TriMesh& target, BuildReport* report, Stopwatch& clock) {
  const SurfaceDistance distance(target);
  const LimitFitResult fit =
      fit_loop_limit(surface, [&distance](const Vec3& p) { return distance.closest_point(p); });
  if (report) {
    report->limit_fitted = true;
    report->limit_fit = fit;
    report->add_stage("limit_fit", clock.lap());
  }
}

TriMesh prepare_mesh(const BodySpec& spec, BuildReport* report) {
  const MeshImport& m = spec.mesh;
  std::vector<std::string> ignored_warnings;
  const std::string file = m.path.string();
  Stopwatch clock;
  // Repaired, largest part, in metres (units guessed when 0).
  const double file_units = (m.units > 0.0 ? m.units : m.scale_given ? 1.0 : 0.0) * m.scale;
  TriMesh surface = import_scan(read_tri_mesh(m.path), file, file_units,
                                report ? report->warnings : ignored_warnings);
  validate_surface(surface, file);  // closed, manifold, outward, no self-intersections
  if (report) {
    report->input_vertices = surface.num_vertices();
    report->input_faces = surface.num_faces();
    report->input_volume = signed_volume(surface);
    report->input_area = surface_area(surface);
    report->add_stage("read", clock.lap());
  }
  for (size_t i = 0; i < m.crop.size(); ++i) {
    try {
      surface = crop_and_cap(surface, {m.crop[i]});
    } catch (const InputError& e) {
      throw InputError(spec_location(spec, "/crop/" + std::to_string(i)), message_of(e));
    }
    if (report && i + 1 == m.crop.size()) report->add_stage("crop", clock.lap());
  }
  const TriMesh target = surface;
  if (m.remesh) {
    check_mesh_budget(surface_area(surface), m.remesh_options.edge_length, "body surface",
                      spec_location(spec, "/edge_length"));
    RemeshResult remeshed;
    try {
      remeshed = remesh_isotropic(surface, m.remesh_options);
    } catch (const InputError& e) {
      throw InputError(spec_location(spec, "/edge_length"), message_of(e));
    }
    surface = std::move(remeshed.mesh);
    if (report) {
      report->feature_edges = remeshed.feature_edges;
      report->remesh_refinements = remeshed.refinements;
      report->add_stage("remesh", clock.lap());
    }
  }
  if (m.fit_limit) fit_limit_to(surface, target, report, clock);
  return surface;
}

}  // namespace

BodySpec parse_body_spec(const nlohmann::json& j, const std::string& json_path,
                         const std::filesystem::path& base_dir, const std::string& source_file,
                         const SkeletonRef& rig) {
  JsonFields fields(j, source_file, json_path);
  return parse_fields(fields, base_dir, rig);
}

BodySpec parse_body_spec(JsonFields& fields, const std::filesystem::path& base_dir,
                         const SkeletonRef& rig) {
  return parse_fields(fields, base_dir, rig);
}

namespace {

/// fn(), with errors about the processed surface (source "surface", e.g. TetGen's)
/// pointing at the spec as a whole.
template <typename Fn>
auto locating_surface_errors(const BodySpec& spec, Fn fn) {
  try {
    return fn();
  } catch (const InputError& e) {
    if (e.source() == "surface") throw InputError(spec_location(spec, ""), message_of(e));
    throw;
  }
}

}  // namespace

TriMesh build_body_surface(const BodySpec& spec, BuildReport* report) {
  return locating_surface_errors(spec, [&] {
    switch (spec.source) {
      case BodySource::kCylinder:
        return generated_surface(spec.cylinder, report);
      case BodySource::kSphere:
        return generated_surface(spec.sphere, report);
      case BodySource::kMesh:
        return prepare_mesh(spec, report);
    }
    throw std::logic_error("build_body_surface: unknown body source");
  });
}

Body build_body_volume(const BodySpec& spec, const TriMesh& surface, BuildReport* report) {
  return locating_surface_errors(spec,
                                 [&] { return body_from_surface(surface, spec.volume, report); });
}

Body build_body(const BodySpec& spec, BuildReport* report) {
  return build_body_volume(spec, build_body_surface(spec, report), report);
}

}  // namespace tightfit
