#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/report/fit_csv.hpp"

#include <vector>

#include <cmath>

#include "tightfit/report/fit_stats.hpp"
#include "tightfit/report/pressure_statistics.hpp"
#include "tightfit/report/seam_statistics.hpp"

#include <algorithm>

#include "tightfit/report/fit_glb.hpp"
#include "tightfit/report/html.hpp"

namespace tightfit {
namespace {

/// min, area-weighted median and max of (value, area) pairs, divided by `scale`.
nlohmann::json range_json(const std::vector<std::pair<double, double>>& v, double scale = 1.0) {
  if (v.empty()) return nullptr;
  double lo = v.front().first, hi = lo;
  for (const auto& [value, area] : v) {
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  return {{"min", lo / scale}, {"median", area_weighted_median(v) / scale}, {"max", hi / scale}};
}

}  // namespace

const VecX& chosen_pressure(const FitAnalysis& fit, ShapeOperatorKind op) {
  return op == ShapeOperatorKind::kMidEdge ? fit.pressure_mid_edge : fit.pressure_limit;
}

std::vector<MeshField> garment_face_fields(const GarmentSimulation& sim, const FitAnalysis& fit,
                                           ShapeOperatorKind op) {
  const auto n = static_cast<Eigen::Index>(fit.elements.size());
  MatX smax(n, 1), smin(n, 1), dir(n, 3), regime(n, 1), tension(n, 1), piece(n, 1);
  for (Eigen::Index e = 0; e < n; ++e) {
    const auto& el = fit.elements[e];
    smax(e, 0) = el.stretch[0];
    smin(e, 0) = el.stretch[1];
    dir.row(e) = el.direction1.transpose();
    regime(e, 0) = static_cast<double>(el.regime);
    tension(e, 0) = el.principal_tension[0];
    piece(e, 0) = sim.garment().topology->triangle_piece[e];
  }
  const VecX& p = chosen_pressure(fit, op);
  return {{"stretch_max", smax},
          {"stretch_min", smin},
          {"stretch_dir", dir},
          {"regime", regime},
          {"tension_max", tension},
          {"pressure_pa", p},
          {"pressure_mmhg", p / kPascalPerMmHg},
          {"pressure_mid_edge_pa", fit.pressure_mid_edge},
          {"pressure_limit_pa", fit.pressure_limit},
          {"piece", piece}};
}

std::vector<MeshField> garment_vertex_fields(const FitAnalysis& fit) {
  return {{"normal_force", fit.vertex_normal_force},
          {"force", MatX(fit.vertex_force)},
          {"vertex_pressure_pa", fit.vertex_pressure}};
}

nlohmann::json fit_statistics(const GarmentSimulation& sim, const FitAnalysis& fit,
                              ShapeOperatorKind op, const std::vector<FitRegion>& regions,
                              const Vec3& up) {
  const VecX& p = chosen_pressure(fit, op);
  const int n = static_cast<int>(fit.elements.size());
  const int pieces = static_cast<int>(sim.garment().pattern.pieces.size());
  // (value, deformed area) samples: every median is area-weighted, as in the report.
  std::vector<std::vector<std::pair<double, double>>> per_piece(pieces);
  std::vector<std::pair<double, double>> all, smax, smin;
  double area[3] = {0, 0, 0}, total = 0, lift_off = 0;
  for (int e = 0; e < n; ++e) {
    const auto& el = fit.elements[e];
    all.emplace_back(p[e], el.deformed_area);
    per_piece[sim.garment().topology->triangle_piece[e]].emplace_back(p[e], el.deformed_area);
    smax.emplace_back(el.stretch[0], el.deformed_area);
    smin.emplace_back(el.stretch[1], el.deformed_area);
    area[static_cast<int>(el.regime)] += el.deformed_area;
    total += el.deformed_area;
    if (p[e] < 0) lift_off += el.deformed_area;
  }
  nlohmann::json j;
  j["pressure_operator"] = op == ShapeOperatorKind::kMidEdge ? "mid_edge" : "limit_surface";
  j["medians"] = "area-weighted (deformed area)";
  j["pressure_pa"] = range_json(all);
  j["pressure_mmhg"] = range_json(all, kPascalPerMmHg);
  {
    std::vector<double> areas(n);
    std::vector<int> faces(n);
    for (int e = 0; e < n; ++e) {
      areas[e] = fit.elements[e].deformed_area;
      faces[e] = e;
    }
    const PressureMoments m = pressure_moments(p, areas, faces);
    j["pressure_pa"]["area_weighted_mean"] = m.mean;
    j["pressure_pa"]["area_weighted_std"] = m.std;
    j["pressure_spread"] = m.mean != 0.0 ? m.std / std::abs(m.mean) : 0.0;
    j["pressure_above_40mmhg_share"] = share_above_warning(p, areas, faces);
  }
  j["stretch_max"] = range_json(smax);
  j["stretch_min"] = range_json(smin);
  j["garment_area_m2"] = total;
  for (const ClothRegime regime : {ClothRegime::kSlack, ClothRegime::kWrinkled, ClothRegime::kTaut})
    j["area_share"][regime_name(regime)] = total > 0 ? area[static_cast<int>(regime)] / total : 0.0;
  j["lift_off_area_m2"] = lift_off;
  j["lift_off_share"] = total > 0 ? lift_off / total : 0.0;
  // Per piece only for garments with real pieces (the cover has one piece per triangle).
  if (pieces <= static_cast<int>(kMaxReportedPieces)) {
    auto& jp = j["pieces"];
    jp = nlohmann::json::array();
    for (int k = 0; k < pieces; ++k)
      jp.push_back({{"name", sim.garment().pattern.pieces[k].name},
                    {"pressure_pa", range_json(per_piece[k])},
                    {"pressure_mmhg", range_json(per_piece[k], kPascalPerMmHg)}});
    j["seams"] = seam_statistics_json(
        fit_seam_statistics(sim.garment(), sim.garment_positions(), sim.materials().fabric, up));
  }
  if (!regions.empty()) {
    std::vector<double> areas(n);
    for (int e = 0; e < n; ++e) areas[e] = fit.elements[e].deformed_area;
    auto& jr = j["pressure_regions"];
    jr = nlohmann::json::array();
    for (const FitRegion& region : regions) jr.push_back(region_statistics_json(region, p, areas));
  }
  return j;
}

nlohmann::json newton_report_json(const NewtonReport& r) {
  nlohmann::json j;
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["chord_steps"] = r.chord_steps;
  j["factorizations"] = r.factorizations;
  j["krylov_iterations"] = r.krylov_iterations;
  j["garment_first_iterations"] = r.garment_first_iterations;
  j["final_energy_j"] = r.final_energy;
  j["final_force_residual_n"] = r.final_force_norm;
  j["force_tolerance_n"] = r.tolerance;
  j["hessian_nonzeros"] = r.hessian_nonzeros;
  j["factor_nonzeros"] = r.factor_nonzeros;
  double t_asm = 0, t_fact = 0, t_solve = 0, t_ls = 0;
  auto& its = j["history"];
  its = nlohmann::json::array();
  for (const auto& it : r.history) {
    its.push_back({{"energy_j", it.energy},
                   {"force_residual_n", it.force_norm},
                   {"step", it.step_size},
                   {"regularization", it.regularization},
                   {"chord", it.chord},
                   {"body_held", it.body_held},
                   {"krylov_iterations", it.krylov_iterations}});
    t_asm += it.seconds_assembly;
    t_fact += it.seconds_factorization;
    t_solve += it.seconds_solve;
    t_ls += it.seconds_line_search;
  }
  j["seconds"] = {{"total", r.seconds_total},
                  {"assembly", t_asm},
                  {"factorization", t_fact},
                  {"solve", t_solve},
                  {"line_search", t_ls}};
  return j;
}

Points3 body_limit_positions(const Body& body, const LimitSurface& surface, const Points3& y) {
  const int ns = body.num_surface_vertices();
  Points3 limit = y.topRows(ns);
  const Triangles& faces = body.surface.faces;
  std::vector<char> placed(static_cast<size_t>(ns), 0);  // each vertex once, from one face
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (placed[static_cast<size_t>(v)]) continue;
      placed[static_cast<size_t>(v)] = 1;
      const SurfacePoint corner{static_cast<int>(f), k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
      limit.row(v) = surface.position(corner, y).transpose();
    }
  return limit;
}

FitView make_fit_view(const GarmentSimulation& sim, const FitAnalysis& fit, ShapeOperatorKind op,
                      const nlohmann::json& parameters, const nlohmann::json& history,
                      const Vec3& up) {
  FitView view;
  // The body as its limit surface (the control mesh pokes out of it, through the
  // garment that lies on it).
  view.body = TriMesh{body_limit_positions(sim.body(), sim.surface(), sim.body_positions()),
                      sim.body().surface.faces};
  view.garment = TriMesh{sim.garment_positions(), sim.garment().topology->garment_triangles};
  view.garment_normals.resize(sim.garment_positions().rows(), 3);
  for (Eigen::Index i = 0; i < view.garment_normals.rows(); ++i)
    view.garment_normals.row(i) = sim.problem().garment_normal(static_cast<int>(i)).transpose();
  view.pinned_vertices = sim.garment().topology->pinned;
  const auto n = static_cast<Eigen::Index>(fit.elements.size());
  MatX smax(n, 1), smin(n, 1), dir(n, 3), regime(n, 1), force(n, 1);
  const VecX& p = chosen_pressure(fit, op);
  for (Eigen::Index e = 0; e < n; ++e) {
    const auto& el = fit.elements[e];
    smax(e, 0) = el.stretch[0];
    smin(e, 0) = el.stretch[1];
    dir.row(e) = el.direction1.transpose();
    regime(e, 0) = static_cast<double>(el.regime);
    force(e, 0) = p[e] * el.deformed_area;
  }
  const FaceField pressure{std::string(fit_fields::kPressurePa), "Pa", p};
  view.garment_fields = {{std::string(fit_fields::kStretchMax), "", smax},
                         {std::string(fit_fields::kStretchMin), "", smin},
                         {std::string(fit_fields::kStretchDirection), "", dir},
                         {std::string(fit_fields::kRegime), "", regime},
                         pressure,
                         pressure_mmhg_field(pressure),
                         {std::string(fit_fields::kNormalForce), "N", force}};
  view.pattern = sim.garment().pattern;
  if (view.pattern.pieces.size() <= kMaxReportedPieces)
    view.seams =
        fit_seam_statistics(sim.garment(), sim.garment_positions(), sim.materials().fabric, up);
  view.parameters = parameters;
  view.history = history;
  return view;
}

std::vector<FieldColoring> fit_report_colorings(const FitView& view) {
  std::vector<FieldColoring> colorings = standard_colorings();
  if (find_field(view.garment_fields, fit_fields::kSlidingExcess))
    colorings.push_back({std::string(fit_fields::kSlidingExcess),
                         "Sliding: tangential force above the friction limit", "N", 1.0,
                         ColorMap::kViridis, 0.0, std::nullopt, true, std::nullopt});
  if (find_field(view.garment_fields, fit_fields::kResidualForce))
    colorings.push_back({std::string(fit_fields::kResidualForce),
                         "Unbalanced force (the solve did not converge)", "N", 1.0,
                         ColorMap::kViridis, 0.0, std::nullopt, true, std::nullopt});
  if (find_field(view.garment_fields, fit_fields::kShapeDistance))
    colorings.push_back({std::string(fit_fields::kShapeDistance), "Distance to the shape target",
                         "mm", 1.0, ColorMap::kViridis, 0.0, std::nullopt, true, std::nullopt});
  return colorings;
}

void write_fit_report(const std::filesystem::path& folder, const FitView& view,
                      const std::string& title) {
  write_fit_glb(folder / "fit.glb", view);
  ReportOptions options;
  options.title = title;
  options.colorings = fit_report_colorings(view);
  write_report_html(folder / "report.html", view, options);
}

void write_fit_meshes(const std::filesystem::path& folder, const GarmentSimulation& sim,
                      const FitAnalysis& fit, ShapeOperatorKind op) {
  TriMesh garment{sim.garment_positions(), sim.garment().topology->garment_triangles};
  PlyAttributes ga;
  ga.face_fields = garment_face_fields(sim, fit, op);
  ga.vertex_fields = garment_vertex_fields(fit);
  // ASCII: Debian's meshio 5 misreads per-face properties of binary PLY (the files are
  // read with it in tests/app/simulate_ply_test.cpp).
  write_ply(folder / "garment.ply", garment, ga, PlyEncoding::ascii);
  write_fit_csv(folder / "garment.csv", sim.garment(), fit.elements, chosen_pressure(fit, op));

  const int ns = sim.body().num_surface_vertices();
  TriMesh body{sim.body_positions().topRows(ns), sim.body().surface.faces};
  PlyAttributes ba;
  const Points3 displacement = sim.body_positions().topRows(ns) - sim.body().surface.vertices;
  ba.vertex_fields.push_back({"displacement", MatX(displacement)});
  ba.vertex_fields.push_back({"displacement_norm", displacement.rowwise().norm()});
  write_ply(folder / "body.ply", body, ba, PlyEncoding::ascii);
}

}  // namespace tightfit
