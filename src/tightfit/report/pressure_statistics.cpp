#include "tightfit/report/pressure_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tightfit/objectives/pressure_regions.hpp"
#include "tightfit/report/fit_stats.hpp"

namespace tightfit {

std::string ral_gz_387_class(double mmhg) {
  if (mmhg < 18.0) return "below I";
  if (mmhg <= 21.0) return "I";
  if (mmhg < 23.0) return "between I and II";
  if (mmhg <= 32.0) return "II";
  if (mmhg < 34.0) return "between II and III";
  if (mmhg <= 46.0) return "III";
  if (mmhg < 49.0) return "between III and IV";
  return "IV";
}

bool in_burn_scar_range(double mmhg) { return mmhg >= 15.0 && mmhg <= 25.0; }
bool in_face_mask_range(double mmhg) { return mmhg >= 20.0 && mmhg <= 32.0; }

PressureMoments pressure_moments(const VecX& p, const std::vector<double>& areas,
                                 const std::vector<int>& faces) {
  PressureMoments m;
  double sum = 0.0, sum_sq = 0.0;
  for (int f : faces) {
    m.area += areas[f];
    sum += areas[f] * p[f];
  }
  if (!(m.area > 0.0)) return m;
  m.mean = sum / m.area;
  for (int f : faces) sum_sq += areas[f] * (p[f] - m.mean) * (p[f] - m.mean);
  m.std = std::sqrt(sum_sq / m.area);
  return m;
}

namespace {

nlohmann::json pressure_summary(double lo, double median, const PressureMoments& m, double hi,
                                double scale) {
  return {{"min", lo / scale},
          {"median", median / scale},
          {"mean", m.mean / scale},
          {"std", m.std / scale},
          {"max", hi / scale}};
}

/// 1, 2 or 5 × 10^k, the smallest such width >= `width`.
double nice_width(double width) {
  const double decade = std::pow(10.0, std::floor(std::log10(width)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= width * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

}  // namespace

double share_above_warning(const VecX& p, const std::vector<double>& areas,
                           const std::vector<int>& faces) {
  double above = 0.0, total = 0.0;
  for (int f : faces) {
    total += areas[f];
    if (p[f] > kPressureWarningMmHg * kPascalPerMmHg) above += areas[f];
  }
  return total > 0.0 ? above / total : 0.0;
}

PressureHistogram pressure_histogram(const VecX& p, const std::vector<double>& areas,
                                     const std::vector<int>& faces, int target_bins) {
  PressureHistogram h;
  if (faces.empty()) return h;
  double lo = p[faces.front()], hi = lo;
  for (int f : faces) {
    lo = std::min(lo, p[f]);
    hi = std::max(hi, p[f]);
  }
  lo /= kPascalPerMmHg;
  hi /= kPascalPerMmHg;
  const double width = nice_width(std::max(hi - lo, 1e-3) / std::max(target_bins, 1));
  // Edges on multiples of the width: 0 is an edge, lift-off bins stay apart.
  const double first = std::floor(lo / width);
  const int bins = std::max(1, static_cast<int>(std::floor(hi / width) - first) + 1);
  for (int k = 0; k <= bins; ++k) h.edges_mmhg.push_back((first + k) * width);
  h.area_m2.assign(bins, 0.0);
  for (int f : faces) {
    const int k = std::clamp(static_cast<int>(std::floor(p[f] / kPascalPerMmHg / width - first)), 0,
                             bins - 1);
    h.area_m2[k] += areas[f];
  }
  return h;
}

std::vector<FitRegion> resolve_fit_regions(const GarmentSimulation& sim,
                                           const PressureRegionSet& regions,
                                           const std::string& source) {
  std::vector<FitRegion> out;
  if (regions.empty()) return out;
  const PressureRegions resolved(sim.garment(), regions.regions, source, regions.rig,
                                 regions.rig_radius);
  const Points3& x = sim.garment_positions();
  const MatX w = resolved.weights(Eigen::Map<const VecX>(x.data(), x.size()));
  for (int r = 0; r < resolved.size(); ++r) {
    FitRegion region{resolved[r].name, resolved[r].min_pa, resolved[r].max_pa, {}};
    for (Eigen::Index e = 0; e < w.cols(); ++e)
      if (w(r, e) >= 0.5) region.faces.push_back(static_cast<int>(e));
    out.push_back(std::move(region));
  }
  return out;
}

nlohmann::json region_statistics_json(const FitRegion& region, const VecX& p,
                                      const std::vector<double>& areas) {
  const std::vector<int>& faces = region.faces;
  nlohmann::json j = {
      {"name", region.name},
      {"faces", faces.size()},
      {"target_pa", {{"min", region.min_pa}, {"max", region.max_pa}}},
      {"target_mmhg",
       {{"min", region.min_pa / kPascalPerMmHg}, {"max", region.max_pa / kPascalPerMmHg}}}};
  const PressureMoments m = pressure_moments(p, areas, faces);
  j["area_m2"] = m.area;
  if (faces.empty()) {
    for (const char* key :
         {"pressure_pa", "pressure_mmhg", "spread", "share_in_target", "lift_off_share",
          "ral_gz_387_class", "burn_scar_range", "face_mask_range", "histogram"})
      j[key] = nullptr;
    return j;
  }
  std::vector<std::pair<double, double>> samples;
  double lo = p[faces.front()], hi = lo, inside = 0.0, lift_off = 0.0;
  for (int f : faces) {
    samples.emplace_back(p[f], areas[f]);
    lo = std::min(lo, p[f]);
    hi = std::max(hi, p[f]);
    if (p[f] >= region.min_pa && p[f] <= region.max_pa) inside += areas[f];
    if (p[f] < 0.0) lift_off += areas[f];
  }
  const double median = area_weighted_median(std::move(samples));
  const double median_mmhg = median / kPascalPerMmHg;
  j["pressure_pa"] = pressure_summary(lo, median, m, hi, 1.0);
  j["pressure_mmhg"] = pressure_summary(lo, median, m, hi, kPascalPerMmHg);
  j["spread"] = m.mean != 0.0 ? m.std / std::abs(m.mean) : 0.0;
  j["share_in_target"] = m.area > 0.0 ? inside / m.area : 0.0;
  j["lift_off_share"] = m.area > 0.0 ? lift_off / m.area : 0.0;
  j["ral_gz_387_class"] = ral_gz_387_class(median_mmhg);
  j["burn_scar_range"] = in_burn_scar_range(median_mmhg);
  j["face_mask_range"] = in_face_mask_range(median_mmhg);
  const PressureHistogram h = pressure_histogram(p, areas, faces);
  j["histogram"] = {{"edges_mmhg", h.edges_mmhg}, {"area_m2", h.area_m2}};
  return j;
}

}  // namespace tightfit
