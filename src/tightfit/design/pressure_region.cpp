#include "tightfit/design/pressure_region.hpp"

namespace tightfit {

void parse_pressure_range(JsonFields& f, double& min_pa, double& max_pa) {
  const bool pa = f.has("min_pa") || f.has("max_pa");
  const bool mmhg = f.has("min_mmhg") || f.has("max_mmhg");
  if (pa == mmhg) f.fail("give the range either as min_pa/max_pa or as min_mmhg/max_mmhg");
  if (pa) {
    min_pa = f.number("min_pa");
    max_pa = f.number("max_pa");
  } else {
    min_pa = f.number("min_mmhg") * kPascalPerMmHg;
    max_pa = f.number("max_mmhg") * kPascalPerMmHg;
  }
  if (max_pa < min_pa) f.fail("the maximum pressure is below the minimum");
}

namespace {

RegionPlane parse_plane(JsonFields f) {
  RegionPlane p;
  p.point = f.vec3("point");
  p.normal = f.vec3("normal");
  if (!(p.normal.norm() > 0.0)) f.fail("must not be zero", "normal");
  p.normal.normalize();
  f.finish();
  return p;
}

}  // namespace

PressureRegion parse_pressure_region(JsonFields f) {
  PressureRegion r;
  r.name = f.string("name");
  if (r.name.empty()) f.fail("must not be empty", "name");
  if (f.has("pieces")) {
    const nlohmann::json& pieces = f.raw("pieces");
    if (!pieces.is_array() || pieces.empty())
      f.fail("expected a non-empty array of piece names", "pieces");
    for (const nlohmann::json& p : pieces) {
      if (!p.is_string() || p.get<std::string>().empty())
        f.fail("expected a non-empty array of piece names", "pieces");
      r.pieces.push_back(p.get<std::string>());
    }
  }
  if (f.has("bones")) {
    const nlohmann::json& bones = f.raw("bones");
    if (!bones.is_array() || bones.empty())
      f.fail("expected a non-empty array of bone names", "bones");
    for (const nlohmann::json& b : bones) {
      if (!b.is_string() || b.get<std::string>().empty())
        f.fail("expected a non-empty array of bone names", "bones");
      r.bones.push_back(b.get<std::string>());
    }
  }
  if (auto p = f.object("above")) r.above = parse_plane(*p);
  if (auto p = f.object("below")) r.below = parse_plane(*p);
  r.transition = f.positive("transition", r.transition, true);
  parse_pressure_range(f, r.min_pa, r.max_pa);
  f.finish();
  return r;
}

}  // namespace tightfit
