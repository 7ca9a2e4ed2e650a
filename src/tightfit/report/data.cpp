#include "tightfit/report/data.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/report/ease_json.hpp"
#include "tightfit/report/encoding.hpp"
#include "tightfit/report/fit_stats.hpp"
#include "tightfit/report/pressure_statistics.hpp"
#include "tightfit/report/seam_statistics.hpp"

namespace tightfit {

namespace {

std::string f32(const std::vector<double>& values) { return "f32:" + base64_float32(values); }
std::string u32(const std::vector<std::int64_t>& values) { return "u32:" + base64_uint32(values); }

template <typename Matrix>
std::vector<double> flat_doubles(const Matrix& m) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.push_back(static_cast<double>(m(r, c)));
  }
  return out;
}

template <typename Matrix>
std::vector<std::int64_t> flat_ints(const Matrix& m) {
  std::vector<std::int64_t> out;
  out.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.push_back(m(r, c));
  }
  return out;
}

nlohmann::json mesh_json(const TriMesh& mesh) {
  return {{"positions", f32(flat_doubles(mesh.vertices))}, {"indices", u32(flat_ints(mesh.faces))}};
}

std::array<int, 3> bytes(const Rgb& rgb) {
  std::array<int, 3> out{};
  for (std::size_t k = 0; k < 3; ++k) out[k] = static_cast<int>(std::lround(255.0 * rgb[k]));
  return out;
}

nlohmann::json coloring_json(const ResolvedColoring& c) {
  nlohmann::json j = {{"field", c.coloring.field},
                      {"label", c.coloring.label},
                      {"unit", c.coloring.unit},
                      {"colormap", colormap_name(c.coloring.colormap)},
                      {"lo", c.lo},
                      {"hi", c.hi},
                      {"data_min", c.data_min},
                      {"data_max", c.data_max},
                      {"range_rule", c.explicit_range ? "fixed" : "percentiles"},
                      {"include_zero", c.coloring.include_zero},
                      {"values", f32(c.values)}};
  if (c.coloring.negative_color) j["negative_color"] = bytes(*c.coloring.negative_color);
  if (c.coloring.colormap == ColorMap::kRegime) {
    nlohmann::json categories = nlohmann::json::array();
    for (const auto& cat : regime_categories()) {
      categories.push_back(
          {{"value", cat.value}, {"label", cat.label}, {"color", bytes(cat.color)}});
    }
    j["categories"] = categories;
  } else {
    std::vector<int> lut;
    for (int i = 0; i < 256; ++i) {
      for (const int b : bytes(colormap_color(c.coloring.colormap, i / 255.0))) lut.push_back(b);
    }
    j["lut"] = lut;
  }
  return j;
}

}  // namespace

nlohmann::json report_data_json(const FitView& view, const std::vector<FieldColoring>& colorings,
                                const std::string& title, const std::string& source) {
  nlohmann::json coloring_list = nlohmann::json::array();
  nlohmann::json missing = nlohmann::json::array();
  for (const auto& coloring : colorings) {
    const FaceField* field = find_field(view.garment_fields, coloring.field);
    if (field == nullptr) {
      missing.push_back(coloring.label + " (field '" + coloring.field + "')");
      continue;
    }
    coloring_list.push_back(coloring_json(resolve_coloring(coloring, *field, source)));
  }

  nlohmann::json pieces = nlohmann::json::array();
  const auto map = resolved_piece_faces(view);
  for (std::size_t k = 0; k < view.pattern.pieces.size(); ++k) {
    const auto& piece = view.pattern.pieces[k];
    std::vector<std::int64_t> faces(map[k].begin(), map[k].end());
    pieces.push_back({{"name", piece.name},
                      {"rest", f32(flat_doubles(piece.rest))},
                      {"triangles", u32(flat_ints(piece.triangles))},
                      {"faces", u32(faces)},
                      {"boundary", piece.boundary},
                      {"holes", piece.holes},
                      {"grain", {piece.grain.x(), piece.grain.y()}}});
    // The piece's seam sides (with the seam's name) and pinned boundaries.
    nlohmann::json edges = nlohmann::json::array();
    for (const Seam& seam : view.pattern.seams)
      for (const SeamSide* side : {&seam.a, &seam.b})
        if (side->piece == static_cast<int>(k))
          edges.push_back({{"kind", "seam"}, {"name", seam.name}, {"vertices", side->vertices}});
    for (const PinnedBoundary& pin : view.pattern.pinned)
      if (pin.piece == static_cast<int>(k))
        edges.push_back({{"kind", "pinned"}, {"name", pin.name}, {"vertices", pin.vertices}});
    pieces.back()["edges"] = edges;
    if (!view.initial_outlines.empty() && view.initial_outlines[k].rows() > 0)
      pieces.back()["initial_outline"] = f32(flat_doubles(view.initial_outlines[k]));
  }

  // Pressure by region and the garment's pressure histogram (mmHg), one definition
  // with result.json (pressure_statistics.hpp).
  nlohmann::json regions = nlohmann::json::array();
  nlohmann::json histogram;
  if (const FaceField* pa = find_field(view.garment_fields, fit_fields::kPressurePa)) {
    const VecX p = pa->values.col(0);
    std::vector<double> areas(static_cast<std::size_t>(view.garment.num_faces()));
    std::vector<int> all(areas.size());
    for (int f = 0; f < view.garment.num_faces(); ++f) {
      areas[f] = face_area(view.garment, f);
      all[f] = f;
    }
    for (const FitRegion& region : view.pressure_regions)
      regions.push_back(region_statistics_json(region, p, areas));
    const PressureHistogram h = pressure_histogram(p, areas, all);
    histogram = {{"edges_mmhg", h.edges_mmhg},
                 {"area_m2", h.area_m2},
                 {"warning_mmhg", kPressureWarningMmHg},
                 {"share_above_warning", share_above_warning(p, areas, all)},
                 {"max_mmhg", p.maxCoeff() / kPascalPerMmHg}};
  }

  nlohmann::json garment_json = mesh_json(view.garment);
  if (view.garment_normals.rows() > 0)
    garment_json["normals"] = f32(flat_doubles(view.garment_normals));
  nlohmann::json poses = nlohmann::json::array();
  for (const FitPose& pose : view.poses)
    poses.push_back({{"name", pose.name},
                     {"garment", f32(flat_doubles(pose.garment))},
                     {"normals", f32(flat_doubles(pose.garment_normals))},
                     {"body", f32(flat_doubles(pose.body))},
                     {"sliding_excess", f32(std::vector<double>(pose.sliding_excess.begin(),
                                                                pose.sliding_excess.end()))},
                     {"sliding_share", pose.sliding_share}});
  return {{"title", title},
          {"body", view.body.num_faces() > 0 ? mesh_json(view.body) : nlohmann::json()},
          {"garment", garment_json},
          {"pinned", view.pinned_vertices},
          {"colorings", coloring_list},
          {"missing_colorings", missing},
          {"pieces", pieces},
          {"stats", fit_statistics_json(compute_fit_statistics(view))},
          {"parameters", view.parameters},
          {"history", view.history},
          {"summary", view.summary},
          {"fabric", view.fabric},
          {"pressure_regions", regions},
          {"pressure_histogram", histogram},
          {"seams", seam_statistics_json(view.seams)},
          {"measurements", ease_table_json(view.measurements)},
          {"silhouettes", view.shape_target.num_faces() == 0
                              ? nlohmann::json()
                              : nlohmann::json{{"target", mesh_json(view.shape_target)},
                                               {"initial", view.initial_garment.num_faces() > 0
                                                               ? mesh_json(view.initial_garment)
                                                               : nlohmann::json()}}},
          {"poses", poses}};
}

}  // namespace tightfit
