#include "tightfit/objectives/resolution.hpp"

namespace tightfit {

ResolutionReference resolution_of(const Garment& garment) {
  const VecX areas = garment_vertex_areas(garment);
  double boundary_length = 0.0;
  int boundary_edges = 0;
  for (const PatternPiece& piece : garment.pattern.pieces)
    for (const std::vector<int>& loop : piece.loops())
      for (size_t k = 0; k < loop.size(); ++k) {
        boundary_length +=
            (piece.rest.row(loop[(k + 1) % loop.size()]) - piece.rest.row(loop[k])).norm();
        ++boundary_edges;
      }
  ResolutionReference r;
  if (areas.size() > 0) r.vertex_area = areas.sum() / static_cast<double>(areas.size());
  if (boundary_edges > 0) r.boundary_edge = boundary_length / boundary_edges;
  return r;
}

ResolutionReference resolution_or_own(const ResolutionReference& reference,
                                      const Garment& garment) {
  return reference.known() ? reference : resolution_of(garment);
}

VecX garment_vertex_areas(const Garment& garment) {
  VecX areas = VecX::Zero(garment.num_garment_vertices());
  const GarmentTopology& topology = *garment.topology;
  for (size_t p = 0; p < garment.pattern.pieces.size(); ++p) {
    const PatternPiece& piece = garment.pattern.pieces[p];
    const int offset = topology.piece_offset[p];
    for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
      const Vec2 a = piece.rest.row(piece.triangles(t, 0)).transpose();
      const Vec2 b = piece.rest.row(piece.triangles(t, 1)).transpose();
      const Vec2 c = piece.rest.row(piece.triangles(t, 2)).transpose();
      const Vec2 e1 = b - a, e2 = c - a;
      const double third = std::abs(e1.x() * e2.y() - e1.y() * e2.x()) / 6.0;
      for (int k = 0; k < 3; ++k)
        areas[topology.pattern_to_garment[static_cast<size_t>(offset + piece.triangles(t, k))]] +=
            third;
    }
  }
  return areas;
}

VecX pinned_vertex_lengths(const Garment& garment) {
  VecX lengths = VecX::Zero(garment.num_garment_vertices());
  const GarmentTopology& topology = *garment.topology;
  for (const PinnedBoundary& pin : garment.pattern.pinned) {
    const PatternPiece& piece = garment.pattern.pieces[static_cast<size_t>(pin.piece)];
    const int offset = topology.piece_offset[static_cast<size_t>(pin.piece)];
    for (size_t k = 1; k < pin.vertices.size(); ++k) {
      const double half =
          0.5 * (piece.rest.row(pin.vertices[k]) - piece.rest.row(pin.vertices[k - 1])).norm();
      for (const int v : {pin.vertices[k - 1], pin.vertices[k]})
        lengths[topology.pattern_to_garment[static_cast<size_t>(offset + v)]] += half;
    }
  }
  return lengths;
}

}  // namespace tightfit
