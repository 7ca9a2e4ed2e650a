#pragma once
/// Triangle meshing of a flat pattern piece with a fixed boundary.
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A meshed piece: the given boundary vertices first (same order), then interior ones.
struct PieceMesh {
  Points2 vertices;     ///< n×2 (m)
  Triangles triangles;  ///< counter-clockwise
};

/// Meshes the interior of the simple counter-clockwise polygon `boundary` (k×2, m)
/// without adding or moving boundary vertices: constrained Delaunay triangulation,
/// Delaunay refinement of the interior (CGAL Mesh_2 without edge refinement) to edges
/// of about `edge_length` and angles of at least ~20° where the boundary allows, then
/// `lloyd_iterations` Lloyd (centroidal Voronoi) smoothing steps of interior vertices.
/// Throws std::invalid_argument for fewer than 3 boundary vertices or a boundary that
/// is not a simple counter-clockwise polygon.
PieceMesh mesh_piece(const Points2& boundary, double edge_length, int lloyd_iterations = 20);

/// Minimum interior angle (degrees) over the triangles; 0 for an empty mesh.
double min_angle_deg(const Points2& vertices, const Triangles& triangles);

}  // namespace tightfit
