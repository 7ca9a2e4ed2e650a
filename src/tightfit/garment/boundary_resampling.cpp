#include "tightfit/garment/boundary_resampling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tightfit {

std::vector<LoopRun> cut_run(const LoopRun& run, const std::function<bool(int)>& is_cut) {
  std::vector<LoopRun> out;
  LoopRun r{run.first, 0};
  for (int e = 0; e < run.count; ++e) {
    ++r.count;
    if (e + 1 < run.count && is_cut(run.first + e + 1)) {
      out.push_back(r);
      r = {run.first + e + 1, 0};
    }
  }
  out.push_back(r);
  return out;
}

int min_edge_count(int runs) { return runs == 1 ? 3 : (runs == 2 ? 2 : 1); }

int edge_count(double length, double edge_length, int min_edges) {
  return std::max(min_edges, static_cast<int>(std::lround(length / edge_length)));
}

int seam_edge_count(double length_a, double length_b, double edge_length, int min_a, int min_b) {
  return std::max(
      {min_a, min_b, static_cast<int>(std::lround(0.5 * (length_a + length_b) / edge_length))});
}

ArcPoint locate_arc(const std::vector<double>& cum, double target) {
  if (cum.size() < 2) throw std::invalid_argument("locate_arc: a polyline needs an edge");
  int e = 0;
  const int edges = static_cast<int>(cum.size()) - 1;
  while (e + 1 < edges && cum[static_cast<size_t>(e + 1)] <= target) ++e;
  const double len = cum[static_cast<size_t>(e + 1)] - cum[static_cast<size_t>(e)];
  const double t =
      len > 0.0 ? std::clamp((target - cum[static_cast<size_t>(e)]) / len, 0.0, 1.0) : 0.0;
  if (t >= 1.0) return {e + 1, 0.0};
  return {e, t};
}

std::vector<ArcPoint> sample_arc(const std::vector<double>& cum, int n) {
  if (n < 1) throw std::invalid_argument("sample_arc: at least one sample is needed");
  std::vector<ArcPoint> out;
  for (int k = 0; k < n; ++k) out.push_back(locate_arc(cum, cum.back() * k / n));
  return out;
}

Points2 polygon_rows(const std::vector<Vec2>& points) {
  Points2 polygon(static_cast<Eigen::Index>(points.size()), 2);
  for (size_t i = 0; i < points.size(); ++i)
    polygon.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return polygon;
}

}  // namespace tightfit
