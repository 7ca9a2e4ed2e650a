#include "tightfit/objectives/pressure_region.hpp"

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

/// A non-empty array of non-empty strings at `key`.
std::vector<std::string> name_list(JsonFields& f, const std::string& key, const std::string& what) {
  const nlohmann::json& list = f.raw(key);
  const std::string expected = "expected a non-empty array of " + what + " names";
  if (!list.is_array() || list.empty()) f.fail(expected, key);
  std::vector<std::string> names;
  for (const nlohmann::json& item : list) {
    if (!item.is_string() || item.get<std::string>().empty()) f.fail(expected, key);
    names.push_back(item.get<std::string>());
  }
  return names;
}

}  // namespace

PressureRegion parse_pressure_region(JsonFields f) {
  PressureRegion r;
  r.name = f.string("name");
  if (r.name.empty()) f.fail("must not be empty", "name");
  if (f.has("pieces")) r.pieces = name_list(f, "pieces", "piece");
  if (f.has("bones")) r.bones = name_list(f, "bones", "bone");
  if (auto p = f.object("above")) r.above = parse_plane(*p);
  if (auto p = f.object("below")) r.below = parse_plane(*p);
  r.transition = f.positive("transition", r.transition, true);
  parse_pressure_range(f, r.min_pa, r.max_pa);
  f.finish();
  return r;
}

}  // namespace tightfit
