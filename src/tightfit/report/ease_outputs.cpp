#include "tightfit/report/ease_outputs.hpp"

#include "tightfit/garment/measurement_levels.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/body_up.hpp"

namespace tightfit {

EaseTable fit_ease_table(const GarmentSimulation& sim, const SceneSpec& scene) {
  const Body& body = sim.body();
  const TriMesh rest_body{body_limit_positions(body, sim.surface(), body.volume.vertices),
                          body.surface.faces};
  const Garment& garment = sim.garment();
  const Points3& fitted = sim.garment_positions();
  EaseTable table;
  if (scene.measurements_given) {
    table = measure_ease(scene.measurements, rest_body, garment, fitted);
  } else {
    if (scene.skeleton)
      table = drop_uncovered(
          measure_ease(skeleton_levels(*scene.skeleton), rest_body, garment, fitted));
    if (table.levels.empty()) {
      const auto levels = plane_levels(TriMesh{fitted, garment.topology->garment_triangles},
                                       body_up_direction(scene.body), kMeasurementSpacing);
      table = drop_uncovered(measure_ease(levels, rest_body, garment, fitted));
    }
  }
  if (garment.pattern.pieces.size() > kMaxReportedPieces)
    for (LevelMeasurement& m : table.levels) m.pieces.clear();
  return table;
}

}  // namespace tightfit
