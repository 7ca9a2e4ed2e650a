#include "tightfit/design/optimization_spec.hpp"

#include "tightfit/common/json_fields.hpp"
#include "tightfit/objectives/pressure_region.hpp"

namespace tightfit {
namespace {

double weight(JsonFields& f) { return f.positive("weight", 1.0, true); }

/// "poses": "neutral" (default) or "all" (the neutral pose and every scene pose).
bool all_poses(JsonFields& f) { return f.choice("poses", {"neutral", "all"}, "neutral") == "all"; }

StretchObjectiveSpec parse_stretch_bounds(JsonFields& f) {
  StretchObjectiveSpec s;
  s.all_poses = all_poses(f);
  s.weight = weight(f);
  s.min_stretch = f.positive("min", 1.0);
  if (f.has("max")) {
    s.max_stretch = f.positive("max");
    if (*s.max_stretch < s.min_stretch) f.fail("must be >= \"min\"", "max");
  }
  return s;
}

StretchObjectiveSpec parse_stretch(JsonFields f) {
  const StretchObjectiveSpec s = parse_stretch_bounds(f);
  f.finish();
  return s;
}

DirectionalStretchObjectiveSpec parse_directional_stretch(JsonFields f) {
  DirectionalStretchObjectiveSpec s;
  s.bounds = parse_stretch_bounds(f);
  s.across_grain = f.choice("direction", {"across_grain", "along_grain"}) == "across_grain";
  f.finish();
  return s;
}

ShapeObjectiveSpec parse_shape(JsonFields f, const std::filesystem::path& base_dir) {
  ShapeObjectiveSpec s;
  s.weight = weight(f);
  const std::string target = f.string("target");
  if (target.empty()) f.fail("must name a mesh file", "target");
  s.target = std::filesystem::path(target);
  if (s.target.is_relative()) s.target = base_dir / s.target;
  s.radius = f.positive("radius", 0.01);
  s.skip_pinned = f.choice("vertices", {"all", "unpinned"}, "all") == "unpinned";
  f.finish();
  return s;
}

PressureObjectiveSpec parse_pressure(JsonFields f) {
  PressureObjectiveSpec s;
  s.weight = weight(f);
  s.scene_regions = !(f.has("min_pa") || f.has("max_pa") || f.has("min_mmhg") || f.has("max_mmhg"));
  if (!s.scene_regions) parse_pressure_range(f, s.min_pa, s.max_pa);
  s.all_poses = all_poses(f);
  f.finish();
  return s;
}

void parse_lbfgs(JsonFields f, PatternOptimizerOptions& o) {
  o.memory = f.integer("memory", o.memory);
  if (o.memory < 1) f.fail("must be >= 1", "memory");
  o.gradient_tolerance = f.positive("gradient_tolerance", o.gradient_tolerance, true);
  o.relative_gradient_tolerance =
      f.positive("relative_gradient_tolerance", o.relative_gradient_tolerance, true);
  o.value_tolerance = f.number("value_tolerance", o.value_tolerance);
  o.relative_decrease_tolerance =
      f.positive("relative_decrease_tolerance", o.relative_decrease_tolerance, true);
  o.stall_iterations = f.integer("stall_iterations", o.stall_iterations);
  if (o.stall_iterations < 1) f.fail("must be >= 1", "stall_iterations");
  o.snap_iterations = f.integer("snap_iterations", o.snap_iterations);
  if (o.snap_iterations < 0) f.fail("must be >= 0", "snap_iterations");
  o.snap_jumps = f.integer("snap_jumps", o.snap_jumps);
  if (o.snap_jumps < 0) f.fail("must be >= 0", "snap_jumps");
  o.gradient_check_tolerance =
      f.positive("gradient_check_tolerance", o.gradient_check_tolerance, true);
  o.max_compression = f.positive("max_compression", o.max_compression, true);
  if (o.max_compression >= 1.0) f.fail("must be in [0, 1)", "max_compression");
  o.max_step = f.positive("max_step", o.max_step, true);
  o.max_step_fraction = f.positive("max_step_fraction", o.max_step_fraction);
  o.step_growth = f.positive("step_growth", o.step_growth, true);
  o.armijo = f.positive("armijo", o.armijo);
  if (o.armijo >= 0.5) f.fail("must be in (0, 0.5)", "armijo");
  o.max_line_search = f.integer("max_line_search", o.max_line_search);
  if (o.max_line_search < 1) f.fail("must be >= 1", "max_line_search");
  f.finish();
}

void parse_remesh(JsonFields f, PatternRemeshOptions& o) {
  o.enabled = f.boolean("enabled", o.enabled);
  o.min_angle_deg = f.positive("min_angle_deg", o.min_angle_deg, true);
  if (o.min_angle_deg >= 60.0) f.fail("must be below 60 degrees", "min_angle_deg");
  o.min_area_fraction = f.positive("min_area_fraction", o.min_area_fraction, true);
  o.edge_length = f.positive("edge_length", o.edge_length, true);
  o.smoothing_iterations = f.integer("smoothing_iterations", o.smoothing_iterations);
  if (o.smoothing_iterations < 0) f.fail("must be >= 0", "smoothing_iterations");
  f.finish();
}

}  // namespace

OptimizationSpec parse_optimization_spec(const nlohmann::json& section, const std::string& file,
                                         const std::string& path,
                                         const std::filesystem::path& base_dir) {
  OptimizationSpec spec;
  spec.optimizer.max_iterations = 50;
  JsonFields f(section, file, path);
  if (auto objectives = f.object("objectives")) {
    if (auto o = objectives->object("stretch")) spec.stretch = parse_stretch(*o);
    if (auto o = objectives->object("directional_stretch"))
      spec.directional_stretch = parse_directional_stretch(*o);
    if (auto o = objectives->object("shape")) spec.shape = parse_shape(*o, base_dir);
    if (auto o = objectives->object("pressure")) spec.pressure = parse_pressure(*o);
    if (auto o = objectives->object("seam_traction")) {
      SeamTractionObjectiveSpec s;
      s.weight = weight(*o);
      o->finish();
      spec.seam_traction = s;
    }
    if (auto o = objectives->object("sliding")) {
      SlidingObjectiveSpec s;
      s.weight = weight(*o);
      s.friction = o->positive("friction", s.friction, true);
      const nlohmann::json& poses = o->raw("poses");
      if (!poses.is_null()) {
        if (!poses.is_array() || poses.empty())
          o->fail("expected a non-empty array of pose names", "poses");
        for (const nlohmann::json& name : poses) {
          if (!name.is_string()) o->fail("expected a non-empty array of pose names", "poses");
          s.poses.push_back(name.get<std::string>());
        }
      }
      o->finish();
      spec.sliding = s;
    }
    objectives->finish();
  }
  if (auto r = f.object("regularizers")) {
    RegularizerWeights& w = spec.regularizers;
    w.seam_length = r->positive("seam_length", 0.0, true);
    w.boundary_spacing = r->positive("boundary_spacing", 0.0, true);
    w.boundary_smoothness = r->positive("boundary_smoothness", 0.0, true);
    w.corner_angle = r->positive("corner_angle", 0.0, true);
    w.pinned_traction = r->positive("pinned_traction", 0.0, true);
    if (auto c = r->object("compactness")) {
      w.compactness = weight(*c);
      w.compactness_options.min_ratio = c->positive("min_ratio", w.compactness_options.min_ratio);
      if (w.compactness_options.min_ratio > 1.0) c->fail("must be in (0, 1]", "min_ratio");
      w.compactness_options.pair_stride =
          c->integer("pair_stride", w.compactness_options.pair_stride);
      if (w.compactness_options.pair_stride < 1) c->fail("must be >= 1", "pair_stride");
      c->finish();
    }
    r->finish();
  }
  spec.optimizer.max_iterations = f.integer("max_iterations", spec.optimizer.max_iterations);
  if (spec.optimizer.max_iterations < 0) f.fail("must be >= 0", "max_iterations");
  spec.optimizer.time_limit = f.positive("time_limit", spec.optimizer.time_limit, true);
  spec.checkpoint_every = f.integer("checkpoint_every", spec.checkpoint_every);
  if (spec.checkpoint_every < 1) f.fail("must be >= 1", "checkpoint_every");
  spec.problem.min_area_ratio = f.positive("min_area_ratio", spec.problem.min_area_ratio);
  if (spec.problem.min_area_ratio >= 1.0) f.fail("must be in (0, 1)", "min_area_ratio");
  if (auto l = f.object("lbfgs")) parse_lbfgs(*l, spec.optimizer);
  if (auto r = f.object("remesh")) parse_remesh(*r, spec.problem.remesh);
  f.finish();

  const RegularizerWeights& w = spec.regularizers;
  const bool any =
      (spec.stretch && spec.stretch->weight > 0) ||
      (spec.directional_stretch && spec.directional_stretch->bounds.weight > 0) ||
      (spec.shape && spec.shape->weight > 0) || (spec.pressure && spec.pressure->weight > 0) ||
      (spec.seam_traction && spec.seam_traction->weight > 0) ||
      (spec.sliding && spec.sliding->weight > 0) || w.seam_length > 0 || w.boundary_spacing > 0 ||
      w.boundary_smoothness > 0 || w.corner_angle > 0 || w.compactness > 0 || w.pinned_traction > 0;
  if (!any) f.fail("no objective or regularizer with a positive weight");
  return spec;
}

}  // namespace tightfit
