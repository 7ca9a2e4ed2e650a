#pragma once
/// Turns a SceneSpec into the objects a simulation needs: the body (built from its
/// spec), the limit surface of its surface, and the garment embedded on it.
#include <memory>
#include <optional>

#include "tightfit/garment/garment_builder.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {

/// A loaded scene. Not movable once built: the simulation keeps references into it.
struct LoadedScene {
  SceneSpec spec;
  Body body;
  BuildReport body_report;
  std::unique_ptr<LimitSurface> surface;
  Garment garment;  ///< the initial garment (embedded)
  /// For layouts: the panels, piece maps and flattening reports the garment came from.
  std::optional<GarmentBuild> build;
  /// Load stages (s): "body" (from the start to the end of the volume), "limit surface",
  /// "garment". The last two run while the body's volume is meshed (2+ threads), so the
  /// stages may sum to more than the load's wall time.
  std::vector<std::pair<std::string, double>> stage_seconds;

  LoadedScene() = default;
  LoadedScene(const LoadedScene&) = delete;
  LoadedScene& operator=(const LoadedScene&) = delete;
};

/// Builds the body, its limit surface and the initial garment; once the body's surface is
/// made, the limit surface and the garment are built on a thread of their own while the
/// calling thread meshes the volume (when thread_count() > 1). The body import's
/// warnings (parts left out, units guessed) are printed to stderr as "warning: ...".
std::unique_ptr<LoadedScene> load_scene(SceneSpec spec);

/// A simulation of the loaded scene's garment (the scene must outlive it).
std::unique_ptr<GarmentSimulation> make_simulation(const LoadedScene& scene);

}  // namespace tightfit
