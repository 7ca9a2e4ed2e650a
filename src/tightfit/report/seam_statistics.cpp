#include "tightfit/report/seam_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "tightfit/physics/seam_traction.hpp"

namespace tightfit {
namespace {

/// Length of the polyline through `vertices` of the piece's rest positions (m).
double side_rest_length(const PatternPiece& piece, const std::vector<int>& vertices) {
  double length = 0.0;
  for (size_t i = 1; i < vertices.size(); ++i)
    length += (piece.rest.row(vertices[i]) - piece.rest.row(vertices[i - 1])).norm();
  return length;
}

std::pair<int, int> sorted_edge(int a, int b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }

}  // namespace

double SeamStatistics::mismatch() const { return std::abs(length_a - length_b); }
double SeamStatistics::stretch_a() const { return length_a > 0.0 ? sewn_length / length_a : 0.0; }
double SeamStatistics::stretch_b() const { return length_b > 0.0 ? sewn_length / length_b : 0.0; }

std::vector<SeamStatistics> pattern_seam_statistics(const Pattern& pattern) {
  std::vector<SeamStatistics> out;
  for (const Seam& seam : pattern.seams) {
    const PatternPiece& a = pattern.pieces[static_cast<size_t>(seam.a.piece)];
    const PatternPiece& b = pattern.pieces[static_cast<size_t>(seam.b.piece)];
    SeamStatistics s;
    s.name = seam.name;
    s.piece_a = a.name;
    s.piece_b = b.name;
    s.length_a = side_rest_length(a, seam.a.vertices);
    s.length_b = side_rest_length(b, seam.b.vertices);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<SeamStatistics> fit_seam_statistics(const Garment& garment, const Points3& x,
                                                const ClothMaterial& material, const Vec3& up) {
  std::vector<SeamStatistics> out = pattern_seam_statistics(garment.pattern);
  // Which seam every seam edge (global pattern vertices, either side) belongs to.
  std::map<std::pair<int, int>, size_t> edge_seam;
  for (size_t k = 0; k < garment.pattern.seams.size(); ++k) {
    const Seam& seam = garment.pattern.seams[k];
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      const int offset = garment.topology->piece_offset[static_cast<size_t>(side->piece)];
      for (size_t i = 1; i < side->vertices.size(); ++i)
        edge_seam[sorted_edge(offset + side->vertices[i - 1], offset + side->vertices[i])] = k;
    }
    // Side a's edges, mapped to the welded garment vertices, are the sewn seam in 3D.
    const int offset = garment.topology->piece_offset[static_cast<size_t>(seam.a.piece)];
    double sewn = 0.0, weighted_angle = 0.0;
    for (size_t i = 1; i < seam.a.vertices.size(); ++i) {
      const int p = garment.topology
                        ->pattern_to_garment[static_cast<size_t>(offset + seam.a.vertices[i - 1])];
      const int q =
          garment.topology->pattern_to_garment[static_cast<size_t>(offset + seam.a.vertices[i])];
      const Vec3 d = (x.row(q) - x.row(p)).transpose();
      const double l = d.norm();
      sewn += l;
      if (l > 0.0) weighted_angle += l * std::acos(std::min(1.0, std::abs(d.dot(up)) / l));
    }
    out[k].sewn_length = sewn;
    out[k].angle_to_up_deg = sewn > 0.0 ? weighted_angle / sewn * 180.0 / std::numbers::pi : 0.0;
    out[k].has_fit = true;
  }
  if (garment.pattern.seams.empty()) return out;

  const std::vector<SeamElement> elements = seam_elements(*garment.topology);
  const VecX flat_x = Eigen::Map<const VecX>(x.data(), x.size());  // row-major: x0 y0 z0 x1 ...
  const Points2 rest = garment.rest_positions();
  const VecX per_element =
      seam_normal_tractions(*garment.topology, elements, FabricLaw(material), flat_x, rest);
  std::vector<double> weighted(out.size(), 0.0), length(out.size(), 0.0);
  for (size_t e = 0; e < elements.size(); ++e) {
    const auto& edge = elements[e].edge;
    const auto it = edge_seam.find(sorted_edge(edge[0], edge[1]));
    if (it == edge_seam.end()) continue;
    const double l0 = (rest.row(edge[1]) - rest.row(edge[0])).norm();
    const double t = per_element[static_cast<Eigen::Index>(e)];
    weighted[it->second] += l0 * t;
    length[it->second] += l0;
    out[it->second].traction_max = std::max(out[it->second].traction_max, t);
  }
  for (size_t k = 0; k < out.size(); ++k) {
    out[k].traction_total = weighted[k];
    out[k].traction_mean = length[k] > 0.0 ? weighted[k] / length[k] : 0.0;
  }
  return out;
}

nlohmann::json seam_statistics_json(const SeamStatistics& s) {
  nlohmann::json j = {{"name", s.name},
                      {"piece_a", s.piece_a},
                      {"piece_b", s.piece_b},
                      {"length_a_mm", 1000.0 * s.length_a},
                      {"length_b_mm", 1000.0 * s.length_b},
                      {"mismatch_mm", 1000.0 * s.mismatch()}};
  if (s.has_fit) {
    j["sewn_length_mm"] = 1000.0 * s.sewn_length;
    j["stretch_a"] = s.stretch_a();
    j["stretch_b"] = s.stretch_b();
    j["traction_mean_n_per_m"] = s.traction_mean;
    j["traction_max_n_per_m"] = s.traction_max;
    j["traction_total_n"] = s.traction_total;
    j["angle_to_up_deg"] = s.angle_to_up_deg;
  }
  return j;
}

nlohmann::json seam_statistics_json(const std::vector<SeamStatistics>& seams) {
  nlohmann::json out = nlohmann::json::array();
  for (const SeamStatistics& s : seams) out.push_back(seam_statistics_json(s));
  return out;
}

}  // namespace tightfit
