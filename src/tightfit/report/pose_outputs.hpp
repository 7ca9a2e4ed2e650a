#pragma once
/// Outputs of a fit in the scene's poses (scene/pose_fit.hpp computes the fit there):
/// for each pose, the garment carried there with its neutral embedding, and the forces
/// the sliding objective looks at.
///
///   garment_pose_NAME.ply   posed garment (m) with per-vertex properties
///                           sliding_excess_n (tangential force above the friction limit, N;
///                           0 on pinned vertices), tangential_n, pressing_n (N)
///   result.json "poses"     per pose: where it came from, the sliding objective T (N²),
///                           the share of free garment vertices whose tangential force
///                           exceeds the friction limit (they would slide), the largest
///                           and median excess (N), the median pressing force (N), the
///                           body's tet volume ratios and inverted tets in the pose
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/report/fit_view.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

struct PoseOutputs {
  nlohmann::json statistics = nlohmann::json::array();  ///< result.json's "poses"
  std::vector<std::string> files;                       ///< file names written
  std::vector<FitPose> views;                           ///< for the report's pose switch
  /// Per garment face, the largest sliding excess over the poses (N): the report's
  /// fit_fields::kSlidingExcess.
  VecX worst_excess;
};

/// Writes the per-pose files of the simulation's current state into `folder` and
/// returns their statistics; nothing when the scene has no poses.
PoseOutputs write_pose_outputs(const std::filesystem::path& folder, const GarmentSimulation& sim,
                               const SceneSpec& scene);

}  // namespace tightfit
