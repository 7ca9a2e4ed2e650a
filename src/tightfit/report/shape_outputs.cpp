#include "tightfit/report/shape_outputs.hpp"

#include <algorithm>
#include <cmath>

#include "tightfit/design/optimization_spec.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/scene/optimization_setup.hpp"

namespace tightfit {
namespace {

VecX distances_to(const ImlsSurface& target, const Points3& x) {
  VecX d(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) d[i] = target.evaluate(x.row(i).transpose()).value;
  return d;
}

nlohmann::json distance_statistics(const VecX& d) {
  if (d.size() == 0) return {{"vertices", 0}};
  return {{"vertices", d.size()},
          {"rms_mm", 1000.0 * std::sqrt(d.squaredNorm() / static_cast<double>(d.size()))},
          {"max_mm", 1000.0 * d.cwiseAbs().maxCoeff()},
          {"mean_signed_mm", 1000.0 * d.mean()}};
}

}  // namespace

std::optional<ShapeComparison> compare_to_shape_target(const SceneSpec& scene,
                                                       const std::string& source, const Points3& x,
                                                       const TriMesh* initial_garment) {
  if (scene.optimize.is_null()) return std::nullopt;
  const OptimizationSpec spec =
      parse_optimization_spec(scene.optimize, source, "/optimize", scene.base_dir);
  if (!spec.shape) return std::nullopt;
  const ImlsSurface surface = read_shape_target(*spec.shape);
  ShapeComparison c;
  c.target_file = spec.shape->target;
  c.target = read_tri_mesh(spec.shape->target);
  c.distance = distances_to(surface, x);
  if (initial_garment) c.initial_distance = distances_to(surface, initial_garment->vertices);
  return c;
}

nlohmann::json shape_statistics_json(const ShapeComparison& c) {
  nlohmann::json j = distance_statistics(c.distance);
  j["target"] = c.target_file.string();
  j["distance"] =
      "signed IMLS distance of every garment vertex to the target (the shape objective's)";
  if (c.initial_distance) j["initial"] = distance_statistics(*c.initial_distance);
  return j;
}

FaceField shape_distance_field(const Triangles& faces, const VecX& distance) {
  MatX values(faces.rows(), 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    values(f, 0) = 1000.0 *
                   (std::abs(distance[faces(f, 0)]) + std::abs(distance[faces(f, 1)]) +
                    std::abs(distance[faces(f, 2)])) /
                   3.0;
  return {std::string(fit_fields::kShapeDistance), "mm", values};
}

}  // namespace tightfit
