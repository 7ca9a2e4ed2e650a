#include "tightfit/report/fabric_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/report/fit_stats.hpp"

namespace tightfit {
namespace {

nlohmann::json curve_json(const FabricCurve& curve) {
  return {{"strain", curve.strains()}, {"tension_n_per_m", curve.tensions()}};
}

/// The curves of one direction sampled for plotting: 65 strains from 0 to `up_to`, the
/// loading and the worn tension at each.
nlohmann::json sampled_json(const FabricCurve& loading, const FabricCurve& worn, double up_to) {
  constexpr int kSamples = 64;
  std::vector<double> strain, load, wear;
  for (int k = 0; k <= kSamples; ++k) {
    const double e = up_to * k / kSamples;
    strain.push_back(e);
    load.push_back(loading.tension(e));
    wear.push_back(worn.tension(e));
  }
  return {{"strain", strain}, {"loading", load}, {"worn", wear}};
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nullptr; }

/// The working point of the faces `faces`: area-weighted median strains and, with a
/// measured knit, the worn curves' tensions there.
nlohmann::json working_point(const std::string& region, const std::vector<int>& faces,
                             const std::vector<ClothElementFit>& elements,
                             const MeasuredFabric* measured) {
  std::vector<std::pair<double, double>> course, wale;
  double area = 0.0;
  for (int f : faces) {
    const ClothElementFit& e = elements[static_cast<std::size_t>(f)];
    course.emplace_back(e.grain_stretch[0] - 1.0, e.deformed_area);
    wale.emplace_back(e.grain_stretch[1] - 1.0, e.deformed_area);
    area += e.deformed_area;
  }
  const double course_strain = area_weighted_median(std::move(course));
  const double wale_strain = area_weighted_median(std::move(wale));
  nlohmann::json c = {{"strain", number_or_null(course_strain)}};
  nlohmann::json w = {{"strain", number_or_null(wale_strain)}};
  if (measured && std::isfinite(course_strain) && std::isfinite(wale_strain)) {
    c["tension_n_per_m"] = measured->worn_course().tension(course_strain);
    w["tension_n_per_m"] = measured->worn_wale().tension(wale_strain);
  }
  return {{"region", region}, {"area_m2", area}, {"course", c}, {"wale", w}};
}

}  // namespace

nlohmann::json fabric_json(const ClothMaterial& worn, const nlohmann::json& document,
                           const std::vector<ClothElementFit>& elements,
                           const std::vector<FitRegion>& regions) {
  const nlohmann::json doc = document.is_object() ? document : nlohmann::json::object();
  const double relaxation = doc.value("relaxation", 0.0);
  nlohmann::json out = {{"thickness_m", worn.thickness}, {"relaxation", relaxation}};
  if (doc.contains("name")) out["name"] = doc["name"];
  if (doc.contains("source")) out["source"] = doc["source"];
  const MeasuredFabric* measured = worn.measured.get();
  if (!measured) {
    out["model"] = "isotropic";
    out["youngs_modulus_pa_simulated"] = worn.youngs_modulus;
    out["youngs_modulus_pa_new"] = worn.youngs_modulus / (1.0 - relaxation);
    out["poisson_ratio"] = worn.poisson_ratio;
  } else {
    out["model"] = "measured";
    out["name"] = measured->name;
    out["coupling"] = measured->coupling;
    out["shear_n_per_m"] = measured->shear_n_per_m;
    out["curves"] = {
        {"course",
         {{"loading", curve_json(measured->course)},
          {"worn", curve_json(measured->worn_course())}}},
        {"wale",
         {{"loading", curve_json(measured->wale)}, {"worn", curve_json(measured->worn_wale())}}}};
  }
  std::vector<int> all(elements.size());
  std::iota(all.begin(), all.end(), 0);
  nlohmann::json points = nlohmann::json::array();
  points.push_back(working_point("garment", all, elements, measured));
  for (const FitRegion& r : regions)
    points.push_back(working_point(r.name, r.faces, elements, measured));
  if (measured) {
    // The plot's range: the measured points and every working point, with a margin.
    double up_to = std::max(measured->course.strains().back(), measured->wale.strains().back());
    for (const nlohmann::json& p : points)
      for (const char* d : {"course", "wale"})
        if (p[d]["strain"].is_number()) up_to = std::max(up_to, 1.1 * p[d]["strain"].get<double>());
    out["curves"]["course"]["sampled"] =
        sampled_json(measured->course, measured->worn_course(), up_to);
    out["curves"]["wale"]["sampled"] = sampled_json(measured->wale, measured->worn_wale(), up_to);
  }
  out["working_points"] = std::move(points);
  return out;
}

}  // namespace tightfit
