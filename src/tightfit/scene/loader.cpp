#include "tightfit/scene/loader.hpp"

#include <cstdio>
#include <future>

#include "tightfit/common/error.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/stopwatch.hpp"

namespace tightfit {
namespace {

/// The initial garment of the scene on its body surface and limit surface.
void build_initial_garment(LoadedScene& scene) {
  const Points3& control = scene.body.surface.vertices;
  const GarmentSpec& g = scene.spec.garment;
  switch (g.kind) {
    case GarmentKind::kSleeve:
      scene.garment = make_sleeve(g.sleeve, *scene.surface, control);
      break;
    case GarmentKind::kCover:
      scene.garment = make_cover(*scene.surface, control, g.cover_scale);
      break;
    case GarmentKind::kLayout: {
      LayoutRig rig;
      if (const SceneRig* scene_rig = scene.spec.rig.get()) {
        rig.skeleton = &scene_rig->skeleton;
        rig.weights = &scene_rig->weights;
        rig.source = scene_rig->source;
      }
      scene.build = build_garment(scene.body.surface, *scene.surface, g.layout, g.pattern, rig);
      for (const std::string& w : scene.build->layout.warnings)
        std::fprintf(stderr, "warning: %s\n", w.c_str());
      scene.garment = scene.build->garment;
      break;
    }
  }
}

}  // namespace

std::unique_ptr<LoadedScene> load_scene(SceneSpec spec) {
  auto scene = std::make_unique<LoadedScene>();
  scene->spec = std::move(spec);
  const auto start = SteadyClock::now();
  scene->body.surface = build_body_surface(scene->spec.body, &scene->body_report);
  for (const std::string& w : scene->body_report.warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());

  // The body's volume (TetGen, the pinned core) and the garment need only the surface: the
  // limit surface and the garment are built on a thread of their own while this one
  // meshes the volume (with one thread, after it). The volume stays on this thread so
  // that its large temporaries are freed into the heap the solves reuse
  // (common/memory_reuse.hpp) rather than into another thread's. The body's errors come
  // first either way: when the volume throws, the future's destructor waits for the
  // garment's thread, and its outcome is dropped.
  double limit_seconds = 0.0, garment_seconds = 0.0;
  const auto build_garment_part = [&scene, &limit_seconds, &garment_seconds] {
    auto t0 = SteadyClock::now();
    scene->surface = std::make_unique<LimitSurface>(scene->body.surface, scene->spec.limit);
    limit_seconds = seconds_since(t0);
    t0 = SteadyClock::now();
    build_initial_garment(*scene);
    garment_seconds = seconds_since(t0);
  };
  std::future<void> garment;
  if (thread_count() > 1) garment = std::async(std::launch::async, build_garment_part);
  Body body = build_body_volume(scene->spec.body, scene->body.surface, &scene->body_report);
  const double body_seconds = seconds_since(start);
  if (garment.valid())
    garment.get();
  else
    build_garment_part();
  scene->body.volume = std::move(body.volume);
  scene->body.pinned = std::move(body.pinned);
  scene->stage_seconds.emplace_back("body", body_seconds);
  scene->stage_seconds.emplace_back("limit surface", limit_seconds);
  scene->stage_seconds.emplace_back("garment", garment_seconds);
  return scene;
}

std::unique_ptr<GarmentSimulation> make_simulation(const LoadedScene& scene) {
  return std::make_unique<GarmentSimulation>(scene.body, *scene.surface, scene.garment,
                                             scene.spec.materials, scene.spec.newton);
}

}  // namespace tightfit
