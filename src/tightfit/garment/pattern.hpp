#pragma once
/// Flat pattern pieces and how they are sewn: the cutter's view of a garment.
/// Rest positions are in metres in the piece's own plane (mm only at export).
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// One flat pattern piece, meshed.
struct PatternPiece {
  std::string name;
  Points2 rest;               ///< n×2 rest positions (m) of the piece's vertices
  Triangles triangles;        ///< counter-clockwise in the (x, y) plane
  std::vector<int> boundary;  ///< the outer boundary loop, counter-clockwise, vertex indices
  /// Openings (a mask's eye holes): loops inside the outer one, each clockwise (the
  /// piece's interior on its left), vertex indices. Their rims are open garment
  /// boundaries: free unless a PinnedBoundary holds them. Empty for most pieces.
  std::vector<std::vector<int>> holes;
  std::vector<int> corners;    ///< boundary vertices that are corners (seam ends, sharp turns)
  Vec2 grain = Vec2::UnitY();  ///< grain-line direction (unit) in piece coordinates

  /// All boundary loops: the outer one first, then the holes.
  std::vector<std::vector<int>> loops() const {
    std::vector<std::vector<int>> all{boundary};
    all.insert(all.end(), holes.begin(), holes.end());
    return all;
  }
  /// Every vertex on a boundary loop (outer loop first, then the holes, in loop order).
  std::vector<int> boundary_vertices() const {
    std::vector<int> all = boundary;
    for (const auto& hole : holes) all.insert(all.end(), hole.begin(), hole.end());
    return all;
  }
};

/// One side of a seam: a boundary polyline of one piece, as vertex indices in order.
struct SeamSide {
  int piece = -1;
  std::vector<int> vertices;
};

/// A seam sews side `a` to side `b`: a.vertices[i] meets b.vertices[i]. Both sides have
/// the same vertex count. The two sides run in opposite boundary directions for
/// pieces of the same orientation.
struct Seam {
  std::string name;
  SeamSide a;
  SeamSide b;
};

/// An open garment boundary held at its place on the body (e.g. a waistband).
struct PinnedBoundary {
  std::string name;
  int piece = -1;
  std::vector<int> vertices;
};

/// All pieces of a garment and their seams.
struct Pattern {
  std::vector<PatternPiece> pieces;
  std::vector<Seam> seams;
  std::vector<PinnedBoundary> pinned;
};

}  // namespace tightfit
