#pragma once
/// The fit against the target surface of a shape objective (paper Sec. 5.1): the signed
/// distance of every garment vertex to the target (the objective's own IMLS distance,
/// imls_surface.hpp), its RMS and maximum for result.json, and the per-face distance map
/// of the report.
///
/// Units: distances in m inside, mm in the JSON and the face field.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/report/fit_view.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {

struct ShapeComparison {
  std::filesystem::path target_file;
  TriMesh target;                        ///< the target surface as read (m)
  VecX distance;                         ///< signed distance per garment vertex (m)
  std::optional<VecX> initial_distance;  ///< per vertex of the initial garment, when given
};

/// The comparison for a scene whose "optimize" section has a shape objective, nullopt
/// otherwise. `x`: garment vertices (n×3, m); `initial_garment` (optional): the garment
/// at the optimization's initial equilibrium. `source` names the scene in errors.
std::optional<ShapeComparison> compare_to_shape_target(const SceneSpec& scene,
                                                       const std::string& source, const Points3& x,
                                                       const TriMesh* initial_garment = nullptr);

/// {"target", "vertices", "rms_mm", "max_mm" (largest |distance|), "mean_signed_mm"
/// (positive: outside the target)} over all garment vertices, and the same under
/// "initial" when the initial distances are known.
nlohmann::json shape_statistics_json(const ShapeComparison& comparison);

/// The report's distance map: per face of `faces`, the mean |distance| of its corners
/// (mm), named fit_fields::kShapeDistance.
FaceField shape_distance_field(const Triangles& faces, const VecX& distance);

}  // namespace tightfit
