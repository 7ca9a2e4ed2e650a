#include "tightfit/garment/pattern_options.hpp"

namespace tightfit {
namespace {

PieceScale read_scale(JsonFields& f, const std::string& key, const nlohmann::json& j,
                      const PieceScale& fallback) {
  if (j.is_null()) return fallback;
  if (!j.is_array() || j.size() != 2 || !j[0].is_number() || !j[1].is_number())
    f.fail("expected [along, across], two positive numbers", key);
  PieceScale s{j[0].get<double>(), j[1].get<double>()};
  if (!(s.along > 0) || !(s.across > 0) || !std::isfinite(s.along) || !std::isfinite(s.across))
    f.fail("scale factors must be positive", key);
  return s;
}

}  // namespace

PatternOptions parse_pattern_options(JsonFields& f) {
  PatternOptions o;
  o.edge_length = f.positive("edge_length", o.edge_length);
  o.scale = read_scale(f, "scale", f.raw("scale"), o.scale);
  if (f.has("grain")) {
    const Vec3 g = f.vec3("grain");
    if (g.norm() < 1e-12) f.fail("the grain direction must not be zero", "grain");
    o.grain = g.normalized();
  }
  const auto& per = f.raw("piece_scale");
  if (!per.is_null()) {
    if (!per.is_object()) f.fail("expected an object {\"piece\": [along, across]}", "piece_scale");
    JsonFields pf(per, f.source(), f.child_path("piece_scale"));
    for (auto it = per.begin(); it != per.end(); ++it)
      o.piece_scale[it.key()] = read_scale(pf, it.key(), pf.raw(it.key()), o.scale);
    pf.finish();
  }
  o.flatten.max_iterations = f.integer("arap_iterations", o.flatten.max_iterations);
  if (o.flatten.max_iterations < 0) f.fail("must not be negative", "arap_iterations");
  o.smoothing_iterations = f.integer("smoothing_iterations", o.smoothing_iterations);
  if (o.smoothing_iterations < 0) f.fail("must not be negative", "smoothing_iterations");
  o.corner_angle_deg = f.positive("corner_angle_deg", o.corner_angle_deg);
  o.flatten_limit_surface = f.boolean("flatten_limit_surface", o.flatten_limit_surface);
  f.finish();
  return o;
}

}  // namespace tightfit
