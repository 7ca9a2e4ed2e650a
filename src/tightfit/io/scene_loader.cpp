#include "tightfit/io/scene_loader.hpp"

#include <cstdio>

#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"

namespace tightfit {
std::unique_ptr<LoadedScene> load_scene(SceneSpec spec) {
  auto scene = std::make_unique<LoadedScene>();
  scene->spec = std::move(spec);
  auto t0 = SteadyClock::now();
  scene->body = build_body(scene->spec.body, &scene->body_report);
  for (const std::string& w : scene->body_report.warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  scene->stage_seconds.emplace_back("body", seconds_since(t0));

  t0 = SteadyClock::now();
  scene->surface = std::make_unique<LimitSurface>(scene->body.surface, scene->spec.limit);
  scene->stage_seconds.emplace_back("limit surface", seconds_since(t0));

  t0 = SteadyClock::now();
  const Points3& control = scene->body.surface.vertices;
  const GarmentSpec& g = scene->spec.garment;
  switch (g.kind) {
    case GarmentKind::kSleeve:
      scene->garment = make_sleeve(g.sleeve, *scene->surface, control);
      break;
    case GarmentKind::kCover:
      scene->garment = make_cover(*scene->surface, control, g.cover_scale);
      break;
    case GarmentKind::kLayout: {
      LayoutRig rig;
      if (const SceneRig* scene_rig = scene->spec.rig.get()) {
        rig.skeleton = &scene_rig->skeleton;
        rig.weights = &scene_rig->weights;
        rig.source = scene_rig->source;
      }
      scene->build = build_garment(scene->body.surface, *scene->surface, g.layout, g.pattern, rig);
      for (const std::string& w : scene->build->layout.warnings)
        std::fprintf(stderr, "warning: %s\n", w.c_str());
      scene->garment = scene->build->garment;
      break;
    }
  }
  scene->stage_seconds.emplace_back("garment", seconds_since(t0));
  return scene;
}

std::unique_ptr<GarmentSimulation> make_simulation(const LoadedScene& scene) {
  return std::make_unique<GarmentSimulation>(scene.body, *scene.surface, scene.garment,
                                             scene.spec.materials, scene.spec.newton);
}

}  // namespace tightfit
