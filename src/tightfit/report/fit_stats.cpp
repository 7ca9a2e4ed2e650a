#include "tightfit/report/fit_stats.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

FaceSetStatistics statistics_of(const std::string& name, const std::vector<int>& faces,
                                const std::vector<double>& areas, const FitView& view) {
  const FaceField* pressure = find_field(view.garment_fields, fit_fields::kPressurePa);
  const FaceField* stretch = find_field(view.garment_fields, fit_fields::kStretchMax);
  const FaceField* regime = find_field(view.garment_fields, fit_fields::kRegime);
  FaceSetStatistics s;
  s.name = name;
  s.faces = static_cast<int>(faces.size());
  for (const int f : faces) s.area += areas[static_cast<std::size_t>(f)];

  s.pressure_min = s.pressure_median = s.pressure_max = kNaN;
  s.liftoff_area = s.liftoff_share = kNaN;
  if (pressure != nullptr) {
    std::vector<std::pair<double, double>> samples;
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    s.liftoff_area = 0.0;
    for (const int f : faces) {
      const double p = pressure->values(f, 0);
      const double a = areas[static_cast<std::size_t>(f)];
      samples.emplace_back(p, a);
      if (!std::isfinite(p)) continue;
      lo = std::min(lo, p);
      hi = std::max(hi, p);
      if (p < 0.0) s.liftoff_area += a;
    }
    if (std::isfinite(lo)) {
      s.pressure_min = lo;
      s.pressure_max = hi;
    }
    s.pressure_median = area_weighted_median(std::move(samples));
    s.liftoff_share = s.area > 0.0 ? s.liftoff_area / s.area : 0.0;
  }

  s.stretch_max_median = s.stretch_max_max = kNaN;
  if (stretch != nullptr) {
    std::vector<std::pair<double, double>> samples;
    for (const int f : faces) {
      const double v = stretch->values(f, 0);
      samples.emplace_back(v, areas[static_cast<std::size_t>(f)]);
      if (std::isfinite(v)) {
        s.stretch_max_max = std::isnan(s.stretch_max_max) ? v : std::max(s.stretch_max_max, v);
      }
    }
    s.stretch_max_median = area_weighted_median(std::move(samples));
  }

  s.slack_share = s.wrinkled_share = s.taut_share = kNaN;
  if (regime != nullptr) {
    double share[3] = {0.0, 0.0, 0.0};
    for (const int f : faces) {
      const double r = regime->values(f, 0);
      if (!std::isfinite(r)) continue;
      const auto k = static_cast<std::size_t>(std::clamp(std::round(r), 0.0, 2.0));
      share[k] += areas[static_cast<std::size_t>(f)];
    }
    const double scale = s.area > 0.0 ? 1.0 / s.area : 0.0;
    s.slack_share = share[0] * scale;
    s.wrinkled_share = share[1] * scale;
    s.taut_share = share[2] * scale;
  }
  return s;
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json face_set_json(const FaceSetStatistics& s) {
  return {
      {"name", s.name},
      {"faces", s.faces},
      {"area_m2", number(s.area)},
      {"pressure_pa",
       {{"min", number(s.pressure_min)},
        {"median", number(s.pressure_median)},
        {"max", number(s.pressure_max)}}},
      {"pressure_mmhg",
       {{"min", number(s.pressure_min / kPascalPerMmHg)},
        {"median", number(s.pressure_median / kPascalPerMmHg)},
        {"max", number(s.pressure_max / kPascalPerMmHg)}}},
      {"stretch_max",
       {{"median", number(s.stretch_max_median)}, {"max", number(s.stretch_max_max)}}},
      {"regime_share",
       {{"slack", number(s.slack_share)},
        {"wrinkled", number(s.wrinkled_share)},
        {"taut", number(s.taut_share)}}},
      {"liftoff_area_m2", number(s.liftoff_area)},
      {"liftoff_share", number(s.liftoff_share)},
  };
}

}  // namespace

double area_weighted_median(std::vector<std::pair<double, double>> value_area) {
  std::erase_if(value_area, [](const auto& p) { return !std::isfinite(p.first); });
  if (value_area.empty()) return kNaN;
  std::sort(value_area.begin(), value_area.end());
  double total = 0.0;
  for (const auto& p : value_area) total += p.second;
  if (total <= 0.0) return value_area[(value_area.size() - 1) / 2].first;
  // Relative slack so that an exact half (up to rounding of the areas) picks the lower value.
  const double half = 0.5 * total * (1.0 - 1e-12);
  double cumulative = 0.0;
  for (const auto& p : value_area) {
    cumulative += p.second;
    if (cumulative >= half) return p.first;
  }
  return value_area.back().first;
}

FitStatistics compute_fit_statistics(const FitView& view) {
  const int n = view.garment.num_faces();
  std::vector<double> areas(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) areas[static_cast<std::size_t>(f)] = face_area(view.garment, f);

  FitStatistics stats;
  const auto map = resolved_piece_faces(view);
  for (std::size_t k = 0; k < map.size(); ++k) {
    stats.pieces.push_back(statistics_of(view.pattern.pieces[k].name, map[k], areas, view));
  }
  std::vector<int> all(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) all[static_cast<std::size_t>(f)] = f;
  stats.garment = statistics_of("garment", all, areas, view);
  return stats;
}

nlohmann::json fit_statistics_json(const FitStatistics& stats) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const auto& piece : stats.pieces) pieces.push_back(face_set_json(piece));
  return {{"garment", face_set_json(stats.garment)}, {"pieces", pieces}};
}

}  // namespace tightfit
