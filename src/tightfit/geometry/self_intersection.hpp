#pragma once
/// Self-intersection test of a triangle surface (CGAL, exact predicates).
#include <array>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Pairs of faces {f, g} (f < g, sorted) that intersect anywhere other than along
/// the edge or at the vertex they share. The mesh must be edge- and vertex-manifold,
/// consistently oriented, without degenerate faces or non-finite coordinates (as
/// checked by surface_problems); std::invalid_argument otherwise.
std::vector<std::array<int, 2>> self_intersecting_face_pairs(const TriMesh& mesh);

}  // namespace tightfit
