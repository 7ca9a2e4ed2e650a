#pragma once
/// The fit of a simulated garment carried into each of the scene's poses
/// (body/posed_body.hpp): the posed garment with its neutral embedding and the forces the
/// sliding objective looks at (objectives/sliding_objective.hpp). The outputs
/// (report/pose_outputs.hpp) write these; they construct no objective themselves.
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

/// The fit in one pose of the scene.
struct PoseFit {
  std::string name;           ///< the pose's name in the scene
  std::string origin;         ///< where the pose came from (ScenePose::origin)
  Points3 garment;            ///< garment vertices in the pose (n_g×3, m)
  Points3 garment_normals;    ///< unit normals of the limit surface there (n_g×3)
  Points3 body;               ///< the body's vertex positions in the pose (n_b×3, m)
  VecX normal;                ///< per garment vertex, the force pressing on the body (N)
  VecX tangential;            ///< per garment vertex, the tangential force (N)
  VecX excess;                ///< per garment vertex, tangential force above μ·f_n (N); 0 pinned
  double volume_ratio = 1.0;  ///< posed / neutral volume of the whole body
  double min_volume_ratio = 1.0;  ///< smallest posed / neutral tet volume
  double max_volume_ratio = 1.0;  ///< largest posed / neutral tet volume
  int inverted_tets = 0;          ///< tets with volume <= 0 in the pose
};

/// The friction coefficient of the scene's sliding objective
/// (optimize.objectives.sliding.friction), else 0.3 (the paper's).
double scene_friction(const SceneSpec& scene);

/// The simulation's current fit carried into every pose of the scene, in the scene's
/// order; empty when the scene has no rig or no poses. Friction: scene_friction.
std::vector<PoseFit> pose_fits(const GarmentSimulation& sim, const SceneSpec& scene);

}  // namespace tightfit
