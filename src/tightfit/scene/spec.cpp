#include "tightfit/scene/spec.hpp"

#include <memory>
#include <numbers>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/mesh_budget.hpp"
#include "tightfit/scene/fabric_spec.hpp"

namespace tightfit {
namespace {

SleeveParams parse_sleeve(JsonFields& f) {
  SleeveParams p;
  p.radius = f.positive("radius", p.radius);
  p.center = f.vec3("center", p.center);
  p.axis = f.vec3("axis", p.axis);
  if (p.axis.norm() == 0.0) f.fail("the axis must not be zero", "axis");
  p.axial_begin = f.number("axial_begin", p.axial_begin);
  p.axial_end = f.number("axial_end", p.axial_end);
  if (!(p.axial_end > p.axial_begin)) f.fail("must be greater than axial_begin", "axial_end");
  p.hoop_scale = f.positive("hoop_scale", p.hoop_scale);
  p.axial_scale = f.positive("axial_scale", p.axial_scale);
  p.edge_length = f.positive("edge_length", p.edge_length);
  p.jitter = f.positive("jitter", p.jitter, true);
  if (p.jitter >= 1.0) f.fail("must be below 1 (a fraction of the grid spacing)", "jitter");
  p.seed = static_cast<unsigned>(f.integer("seed", static_cast<int>(p.seed)));
  p.rotation = f.number("rotation", p.rotation);
  p.twist = f.number("twist", p.twist);
  p.pin_first_ring = f.boolean("pin_first_ring", p.pin_first_ring);
  p.pin_last_ring = f.boolean("pin_last_ring", p.pin_last_ring);
  const double rest_area = 2.0 * std::numbers::pi * p.radius * p.hoop_scale *
                           (p.axial_end - p.axial_begin) * p.axial_scale;
  if (const std::string problem = mesh_budget_problem(rest_area, p.edge_length, "sleeve");
      !problem.empty())
    f.fail(problem, "edge_length");
  f.finish();
  return p;
}

GarmentSpec parse_garment(JsonFields& f, const std::filesystem::path& base_dir) {
  GarmentSpec g;
  g.json_path = f.path();
  int kinds = 0;
  if (auto s = f.object("sleeve")) {
    g.kind = GarmentKind::kSleeve;
    g.sleeve = parse_sleeve(*s);
    ++kinds;
  }
  if (auto c = f.object("cover")) {
    g.kind = GarmentKind::kCover;
    g.cover_scale = c->positive("scale", 0.9);
    c->finish();
    ++kinds;
  }
  if (f.has("layout") && f.raw("layout").is_string()) {
    // A layout file of its own, e.g. one layout anchored on the skeleton for every body.
    const std::string name = f.raw("layout").get<std::string>();
    if (name.empty()) f.fail("must name a file", "layout");
    std::filesystem::path file(name);
    if (file.is_relative()) file = base_dir / file;
    if (!std::filesystem::is_regular_file(file)) f.fail("no such file: " + file.string(), "layout");
    g.kind = GarmentKind::kLayout;
    g.layout = read_layout_spec(file.string());
    ++kinds;
  } else if (auto l = f.object("layout")) {
    g.kind = GarmentKind::kLayout;
    g.layout = parse_layout_spec(*l, base_dir.string());
    ++kinds;
  }
  if (auto p = f.object("pattern")) {
    if (g.kind != GarmentKind::kLayout || kinds == 0)
      f.fail("only goes with a \"layout\"", "pattern");
    g.pattern = parse_pattern_options(*p);
  }
  if (kinds != 1) f.fail("needs exactly one of \"sleeve\", \"cover\" or \"layout\"");
  f.finish();
  return g;
}

/// The stiffest material a scene may name (Pa): beyond any fabric, skin or foam by far,
/// and low enough that energies, forces and their derivatives stay finite.
constexpr double kMaxModulus = 1e12;
constexpr const char* kModulusWhy = "stiffer than steel, about 2e11 Pa: not a garment or a body";
/// The thickest fabric or seam a scene may name (m).
constexpr double kMaxThickness = 0.1;

void parse_seam(JsonFields& f, SeamMaterial& m) {
  m.youngs_modulus =
      f.at_most("youngs_modulus", f.positive("youngs_modulus", m.youngs_modulus, true), kMaxModulus,
                kModulusWhy);
  m.width = f.at_most("width", f.positive("width", m.width), kMaxThickness,
                      "a seam is narrower than 10 cm");
  m.depth = f.at_most("thickness", f.positive("thickness", m.depth), kMaxThickness,
                      "a seam is thinner than 10 cm");
  f.finish();
}

void parse_body_material(JsonFields& f, NeoHookeanMaterial& m, bool& rigid) {
  m.youngs_modulus = f.at_most("youngs_modulus", f.positive("youngs_modulus", m.youngs_modulus),
                               kMaxModulus, kModulusWhy);
  m.poisson_ratio = f.number("poisson_ratio", m.poisson_ratio);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    f.fail("must lie in (-1, 0.5) for a solid", "poisson_ratio");
  rigid = f.boolean("rigid", rigid);
  f.finish();
}

void parse_solver(JsonFields& f, NewtonOptions& n, LimitSurfaceOptions& l) {
  n.relative_force_tolerance = f.positive("relative_force_tolerance", n.relative_force_tolerance);
  n.absolute_force_tolerance = f.positive("absolute_force_tolerance", n.absolute_force_tolerance);
  n.max_iterations = f.integer("max_iterations", n.max_iterations);
  if (n.max_iterations < 1) f.fail("must be at least 1", "max_iterations");
  l.approx_level_smooth = f.integer("limit_level", l.approx_level_smooth);
  if (l.approx_level_smooth < 1 || l.approx_level_smooth > 10)
    f.fail("must be in 1..10", "limit_level");
  l.approx_level_sharp = std::max(l.approx_level_sharp, l.approx_level_smooth);
  f.finish();
}

}  // namespace

SceneSpec parse_scene(const nlohmann::json& document, const std::string& file,
                      const std::filesystem::path& base_dir) {
  SceneSpec s;
  s.file = file;
  s.base_dir = base_dir;
  s.document = document;
  JsonFields root(document, file, "");
  root.string("$schema", std::string());
  root.string("description", std::string());
  if (auto f = root.object("rig")) s.rig = parse_scene_rig(*f, base_dir);
  auto body = root.object("body", true);
  s.body = parse_body_spec(*body, base_dir,
                           s.rig ? SkeletonRef{&s.rig->skeleton, s.rig->source} : SkeletonRef{});
  if (const nlohmann::json& b = document.at("body");
      b.contains("skeleton") && b["skeleton"].is_string()) {
    const std::filesystem::path joints = base_dir / b["skeleton"].get<std::string>();
    s.skeleton = std::make_shared<const std::map<std::string, BoneSegment>>(read_skeleton(joints));
    s.skeleton_source = joints.string();
  } else if (s.rig) {
    s.skeleton = std::shared_ptr<const std::map<std::string, BoneSegment>>(s.rig, &s.rig->skeleton);
    s.skeleton_source = s.rig->source;
  }
  auto garment = root.object("garment", true);
  s.garment = parse_garment(*garment, base_dir);
  if (root.has("fabric")) {
    // A fabric file is read once and inlined, so that the run's saved scene (state.json,
    // checkpoints, --resume) carries the curves it was run with.
    FabricSpec fabric = parse_fabric_spec(root.raw("fabric"), file, "/fabric", base_dir);
    s.materials.fabric = fabric.material;
    s.fabric_file = fabric.file;
    s.document["fabric"] = fabric.document;
  }
  if (auto f = root.object("seam")) parse_seam(*f, s.materials.seam);
  if (auto f = root.object("body_material"))
    parse_body_material(*f, s.materials.body, s.materials.rigid_body);
  if (auto f = root.object("solver")) parse_solver(*f, s.newton, s.limit);
  if (root.has("poses"))
    s.poses = parse_scene_poses(root.raw("poses"), file, "/poses", s.rig.get(), base_dir);
  if (s.rig) s.pressure_rig = std::shared_ptr<const SkinWeights>(s.rig, &s.rig->weights);
  if (s.garment.kind == GarmentKind::kLayout && !s.rig) {
    const std::string use = s.garment.layout.first_rig_use();
    if (!use.empty())
      throw InputError(s.garment.layout.source,
                       use +
                           ": anchored on the skeleton or its skin weights, but the scene has no "
                           "\"rig\" (\"rig\": {\"mesh\", \"weights\", \"joints\"})");
  }
  if (auto f = root.object("pressure")) {
    s.pressure_operator =
        f->choice("shape_operator", {"mid_edge", "limit_surface"}, "mid_edge") == "mid_edge"
            ? ShapeOperatorKind::kMidEdge
            : ShapeOperatorKind::kLimitSurface;
    for (JsonFields& region : f->objects("regions", false, kMaxSceneParts))
      s.pressure_regions.push_back(parse_pressure_region(region));
    if (auto rig = f->object("rig")) {
      auto resolve = [&](const std::string& key) {
        const std::string name = rig->string(key);
        if (name.empty()) rig->fail("must name a file", key);
        std::filesystem::path p(name);
        return p.is_relative() ? base_dir / p : p;
      };
      const std::filesystem::path mesh = resolve("mesh"), weights = resolve("weights");
      s.pressure_rig_radius = rig->positive("radius", s.pressure_rig_radius);
      rig->finish();
      s.pressure_rig = std::make_shared<const SkinWeights>(read_skin_weights(mesh, weights));
    }
    for (std::size_t k = 0; k < s.pressure_regions.size(); ++k)
      if (!s.pressure_regions[k].bones.empty() && !s.pressure_rig)
        f->fail("names bones but the scene has no /rig or /pressure/rig",
                "regions/" + std::to_string(k) + "/bones");
    f->finish();
  }
  if (root.has("measurements")) {
    s.measurements_given = true;
    s.measurements = parse_measurement_levels(
        root, "measurements",
        s.skeleton ? SkeletonRef{s.skeleton.get(), s.skeleton_source} : SkeletonRef{});
  }
  s.patterns.file = file;
  s.patterns.json_path = "/patterns";
  if (auto f = root.object("patterns")) s.patterns = parse_pattern_export_spec(*f);
  if (root.has("optimize")) {
    s.optimize = root.raw("optimize");
    if (!s.optimize.is_object()) root.fail("expected an object", "optimize");
  }
  root.finish();
  return s;
}

SceneSpec read_scene(const std::filesystem::path& file) {
  const nlohmann::json doc = read_json_file(file.string());
  auto base = file.parent_path();
  if (base.empty()) base = ".";
  return parse_scene(doc, file.string(), base);
}

}  // namespace tightfit
