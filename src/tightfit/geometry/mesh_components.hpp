#pragma once
/// Connected components of a triangle mesh (faces connected through shared vertices),
/// for body scans that arrive as several surfaces (a body and a floor, loose parts).
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// One component: its faces' vertices renumbered from 0 in order of first use.
struct MeshComponent {
  TriMesh mesh;
  std::vector<int> faces;  ///< the input faces it holds, ascending
};

/// The components, largest face count first (ties: lower first face first). Vertices
/// no face uses belong to none.
std::vector<MeshComponent> connected_components(const TriMesh& mesh);

}  // namespace tightfit
