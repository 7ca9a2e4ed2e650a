#include "tightfit/body/body_stats.hpp"

#include <algorithm>
#include <vector>

#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit {
namespace {

double min_dihedral_of_tet(const TetMesh& mesh, int t) {
  const auto angles =
      tet_dihedral_angles(mesh.vertices.row(mesh.tets(t, 0)), mesh.vertices.row(mesh.tets(t, 1)),
                          mesh.vertices.row(mesh.tets(t, 2)), mesh.vertices.row(mesh.tets(t, 3)));
  return *std::min_element(angles.begin(), angles.end());
}

}  // namespace

BodyStats compute_body_stats(const Body& body) {
  BodyStats s;
  s.surface_vertices = body.surface.num_vertices();
  s.surface_faces = body.surface.num_faces();
  s.volume_vertices = body.volume.num_vertices();
  s.tets = body.volume.num_tets();
  s.pinned = static_cast<int>(body.pinned.size());
  s.surface_area = surface_area(body.surface);
  s.surface_volume = signed_volume(body.surface);
  s.mean_surface_edge = edge_length_stats(body.surface).mean;
  const VecX volumes = tet_volumes(body.volume);
  s.tet_volume = total_volume(body.volume);
  s.inverted_tets = static_cast<int>((volumes.array() <= 0.0).count());
  s.min_tet_volume = volumes.size() > 0 ? volumes.minCoeff() : 0.0;
  const AngleRange angles = dihedral_angle_range(body.volume);
  s.min_dihedral_deg = angles.min_degrees;
  s.max_dihedral_deg = angles.max_degrees;
  VecX ratios = radius_edge_ratios(body.volume);
  if (ratios.size() > 0) {
    std::vector<double> sorted(ratios.data(), ratios.data() + ratios.size());
    std::sort(sorted.begin(), sorted.end());
    s.min_radius_edge = sorted.front();
    s.max_radius_edge = sorted.back();
    s.mean_radius_edge = ratios.mean();
    s.p99_radius_edge = sorted[static_cast<size_t>(0.99 * static_cast<double>(sorted.size() - 1))];
  }
  return s;
}

std::vector<MeshField> body_cell_fields(const Body& body) {
  MeshField volume{"volume", tet_volumes(body.volume)};
  MeshField dihedral{"min_dihedral", MatX(body.volume.num_tets(), 1)};
  for (int t = 0; t < body.volume.num_tets(); ++t)
    dihedral.values(t, 0) = min_dihedral_of_tet(body.volume, t);
  return {volume, dihedral};
}

std::vector<MeshField> body_point_fields(const Body& body) {
  MeshField pinned{"pinned", MatX::Zero(body.num_vertices(), 1)};
  for (int v : body.pinned) pinned.values(v, 0) = 1.0;
  MeshField surface{"surface", MatX::Zero(body.num_vertices(), 1)};
  surface.values.topRows(body.num_surface_vertices()).setOnes();
  return {pinned, surface};
}

nlohmann::json body_summary_json(const BodyStats& s, const BuildReport& report) {
  nlohmann::json j;
  j["units"] = "SI: lengths m, areas m^2, volumes m^3, angles degrees, times s";
  j["warnings"] = report.warnings;
  j["counts"] = {{"surface_vertices", s.surface_vertices},
                 {"surface_faces", s.surface_faces},
                 {"volume_vertices", s.volume_vertices},
                 {"tets", s.tets},
                 {"pinned_vertices", s.pinned},
                 {"bone_points", report.bone_points}};
  j["surface"] = {{"area", s.surface_area},
                  {"volume", s.surface_volume},
                  {"mean_edge_length", s.mean_surface_edge}};
  j["tets"] = {{"volume", s.tet_volume},
               {"inverted", s.inverted_tets},
               {"min_volume", s.min_tet_volume},
               {"min_dihedral", s.min_dihedral_deg},
               {"max_dihedral", s.max_dihedral_deg},
               {"radius_edge",
                {{"min", s.min_radius_edge},
                 {"mean", s.mean_radius_edge},
                 {"p99", s.p99_radius_edge},
                 {"max", s.max_radius_edge}}},
               {"tetgen_switches", report.tetgen_switches}};
  j["input"] = {
      {"vertices", report.input_vertices},     {"faces", report.input_faces},
      {"volume", report.input_volume},         {"area", report.input_area},
      {"feature_edges", report.feature_edges}, {"remesh_refinements", report.remesh_refinements}};
  if (report.limit_fitted)
    j["limit_fit"] = {{"iterations", report.limit_fit.iterations},
                      {"max_residual", report.limit_fit.max_residual},
                      {"max_displacement", report.limit_fit.max_displacement}};
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& [stage, seconds] : report.stage_seconds) timings[stage] = seconds;
  timings["total"] = report.total_seconds();
  j["timings"] = timings;
  return j;
}

}  // namespace tightfit
