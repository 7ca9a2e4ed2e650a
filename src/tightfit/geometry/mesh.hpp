#pragma once
/// Plain mesh containers shared by every layer. Topology queries live in separate
/// classes (see surface_topology.hpp); these hold only arrays.
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A triangle surface mesh. `vertices` n×3 (m), `faces` m×3 vertex indices,
/// counter-clockwise seen from outside for closed surfaces.
struct TriMesh {
  Points3 vertices;
  Triangles faces;

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
};

/// A tetrahedral volume mesh. `vertices` n×3 (m), `tets` m×4 vertex indices with
/// positive orientation: (v1-v0)·((v2-v0)×(v3-v0)) > 0.
struct TetMesh {
  Points3 vertices;
  Tetrahedra tets;

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_tets() const { return static_cast<int>(tets.rows()); }
};

}  // namespace tightfit
