#pragma once
/// Rigid bodies for the analytic tests of the forward simulation: a body whose every
/// vertex is held (the surface alone, no tetrahedra) and the materials that say so.
#include <utility>

#include "tightfit/body/body.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::test {

inline Body rigid_body(TriMesh surface) {
  Body body;
  body.surface = std::move(surface);
  body.volume.vertices = body.surface.vertices;
  body.volume.tets.resize(0, 4);
  return body;
}

inline SimulationMaterials rigid_materials() {
  SimulationMaterials m;
  m.rigid_body = true;
  return m;
}

}  // namespace tightfit::test
