#include "tightfit/report/pose_outputs.hpp"

#include <algorithm>

#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"
#include "tightfit/report/fit_csv.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/pose_fit.hpp"

namespace tightfit {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

PoseOutputs write_pose_outputs(const std::filesystem::path& folder, const GarmentSimulation& sim,
                               const SceneSpec& scene) {
  PoseOutputs out;
  const std::vector<PoseFit> fits = pose_fits(sim, scene);
  if (fits.empty()) return out;
  const double friction = scene_friction(scene);
  const Triangles& faces = sim.garment().topology->garment_triangles;
  out.worst_excess = VecX::Zero(faces.rows());
  std::vector<char> pinned(static_cast<std::size_t>(sim.garment().num_garment_vertices()), 0);
  for (int v : sim.garment().topology->pinned) pinned[static_cast<std::size_t>(v)] = 1;
  for (const PoseFit& fit : fits) {
    const TriMesh mesh{fit.garment, faces};
    PlyAttributes attributes;
    attributes.vertex_fields = {{"sliding_excess_n", fit.excess},
                                {"tangential_n", fit.tangential},
                                {"pressing_n", fit.normal}};
    const std::string file = "garment_pose_" + fit.name + ".ply";
    write_ply(folder / file, mesh, attributes);
    out.files.push_back(file);
    // Stretch and pressure (mid-edge operator of the posed garment) per face, as CSV.
    const VecX flat = Eigen::Map<const VecX>(fit.garment.data(), fit.garment.size());
    const std::vector<ClothElementFit> elements = analyze_cloth(sim.cloth(), flat);
    const VecX pressure =
        young_laplace_pressure(elements, mid_edge_shape_operators(fit.garment, faces));
    VecX face_excess(faces.rows());
    for (Eigen::Index t = 0; t < faces.rows(); ++t)
      face_excess[t] =
          (fit.excess[faces(t, 0)] + fit.excess[faces(t, 1)] + fit.excess[faces(t, 2)]) / 3.0;
    const std::string table = "garment_pose_" + fit.name + ".csv";
    write_fit_csv(folder / table, sim.garment(), elements, pressure, &face_excess);
    out.files.push_back(table);
    std::vector<double> excess, pressing;
    int sliding_vertices = 0;
    double value = 0.0;
    for (int j = 0; j < fit.excess.size(); ++j) {
      if (pinned[static_cast<std::size_t>(j)]) continue;
      excess.push_back(fit.excess[j]);
      pressing.push_back(fit.normal[j]);
      value += fit.excess[j] * fit.excess[j];
      if (fit.excess[j] > 0.0) ++sliding_vertices;
    }
    const double sliding_share =
        excess.empty() ? 0.0
                       : static_cast<double>(sliding_vertices) / static_cast<double>(excess.size());
    FitPose view;
    view.name = fit.name;
    view.garment = fit.garment;
    view.garment_normals = fit.garment_normals;
    view.body = body_limit_positions(sim.body(), sim.surface(), fit.body);
    view.sliding_excess = face_excess;
    out.worst_excess = out.worst_excess.cwiseMax(view.sliding_excess);
    view.sliding_share = sliding_share;
    out.views.push_back(std::move(view));
    out.statistics.push_back(
        {{"name", fit.name},
         {"from", fit.origin},
         {"friction", friction},
         {"sliding_objective_n2", value},
         {"free_vertices", excess.size()},
         {"sliding_share", sliding_share},
         {"excess_n",
          {{"max", excess.empty() ? 0.0 : *std::max_element(excess.begin(), excess.end())},
           {"median", median(excess)}}},
         {"pressing_n_median", median(pressing)},
         {"body",
          {{"volume_ratio", fit.volume_ratio},
           {"tet_volume_ratio", {{"min", fit.min_volume_ratio}, {"max", fit.max_volume_ratio}}},
           {"inverted_tets", fit.inverted_tets}}},
         {"file", file}});
  }
  return out;
}

}  // namespace tightfit
