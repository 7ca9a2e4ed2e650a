#pragma once
/// A simulated body: its surface (the Loop control mesh on which the garment lives),
/// its tetrahedral volume and the pinned "bone" core that keeps it from floating.
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Invariant: the first `surface.num_vertices()` vertices of `volume` are the surface
/// vertices in the same order (surface vertex i == volume vertex i), so a body state y
/// (volume.num_vertices()×3) also gives the control points of the limit surface.
struct Body {
  TriMesh surface;          ///< closed, outward-oriented control mesh (m)
  TetMesh volume;           ///< tets over all body vertices (m)
  std::vector<int> pinned;  ///< volume vertex indices held fixed (sorted, unique)

  int num_surface_vertices() const { return surface.num_vertices(); }
  int num_vertices() const { return volume.num_vertices(); }
};

}  // namespace tightfit
