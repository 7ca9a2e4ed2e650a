#pragma once
/// Triangle meshing of a flat pattern piece with a fixed boundary.
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// A meshed piece: the given boundary vertices first (outer loop, then each hole, in the
/// given order), then interior ones.
struct PieceMesh {
  Points2 vertices;     ///< n×2 (m)
  Triangles triangles;  ///< counter-clockwise
};

/// Meshes the interior of the simple counter-clockwise polygon `boundary` (k×2, m)
/// without adding or moving boundary vertices. Interior points start on an equilateral
/// lattice of spacing `edge_length` (those closer than half a spacing to the boundary
/// are dropped), are connected by a constrained Delaunay triangulation (CGAL), and are
/// then moved by `smoothing_iterations` steps of optimal-Delaunay smoothing (each
/// vertex to the area-weighted mean of its triangles' circumcentres, unless that would
/// fold a triangle), re-triangulating after each step; last, every interior edge between
/// two boundary vertices is split at its midpoint (boundary_chords.hpp), so that no seam
/// weld can give an edge more than two faces. The result is deterministic: it
/// depends only on the input numbers. Throws std::invalid_argument for fewer than 3
/// boundary vertices or a boundary that is not a simple counter-clockwise polygon.
PieceMesh mesh_piece(const Points2& boundary, double edge_length, int smoothing_iterations = 10);

/// The same for a piece with holes (openings): `holes` are simple clockwise polygons
/// (k_i×2, m; the piece's interior on their left, like the outer loop's) inside
/// `boundary`, neither crossing nor touching it or each other. Throws
/// std::invalid_argument naming the hole that is too short, counter-clockwise or
/// outside the outer boundary, and for loops that cross or touch.
PieceMesh mesh_piece(const Points2& boundary, const std::vector<Points2>& holes, double edge_length,
                     int smoothing_iterations = 10);

/// Minimum interior angle (degrees) over the triangles; 0 for an empty mesh.
double min_angle_deg(const Points2& vertices, const Triangles& triangles);

}  // namespace tightfit
