#pragma once
/// Oriented points spread over a triangle surface, no farther apart than a given
/// spacing: what a point-based implicit surface (the IMLS distance of the shape
/// objective) needs from a target mesh whatever the mesh's own resolution.
#include <cstdint>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Points on a surface (k×3, m) and a unit normal at each (k×3).
struct OrientedPoints {
  Points3 points;
  Points3 normals;
};

/// Samples `mesh` so that neighbouring samples are at most `spacing` (m) apart:
///   * every vertex that a face with non-zero area uses, once;
///   * every edge of length L, divided into n_e = ⌈L / spacing⌉ equal parts: its n_e − 1
///     inner points, once (shared by the faces on both sides);
///   * every face of non-zero area, on the barycentric grid of level n_f (the largest n_e
///     of its edges): the points (i a + j b + k c) / n_f with i, j, k ≥ 1.
/// A mesh whose edges are all at most `spacing` long gives its vertices only.
///
/// The mesh is taken as a discretization of a smooth surface, not as its flat facets:
/// a point with barycentric weights w over the vertices p_i (normals n_i) is placed by
/// Phong tessellation (Boubekeur & Alexa 2008) with α = ½,
///   p = ½ Σ w_i p_i + ½ Σ w_i π_i(Σ w_j p_j),  π_i(q) = q − ((q − p_i)·n_i) n_i,
/// the value that reproduces curvature to second order: on a circle of radius R the
/// chord's midpoint sags s²/8R inside, the tangent projections lift it s²/4R, and half
/// of that lift puts it back on the circle. (Flat facets would put a coarse target's face
/// centres inside the surface its vertices lie on.) Vertices stay where they are, edge
/// points depend on their edge only, so the sampled surface has no cracks.
/// Normals are the area-weighted vertex normals (vertex_normals) interpolated
/// barycentrically and normalized: a field that turns smoothly across edges, where the
/// face normals would jump. Order: vertices (ascending), edge points, face points.
OrientedPoints sample_surface(const TriMesh& mesh, double spacing);

/// The number of points sample_surface(mesh, spacing) returns, computed without making
/// them (to refuse a sampling that would not fit in memory before allocating it).
std::int64_t count_surface_samples(const TriMesh& mesh, double spacing);

}  // namespace tightfit
