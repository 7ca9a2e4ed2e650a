#pragma once
/// The two ways between a pattern piece and its 3D layout panel, for the tests that
/// check the piece maps of the pattern builder are inverse to each other.
#include <limits>

#include "tightfit/garment/pattern_builder.hpp"
#include "tightfit/garment/triangle_geometry.hpp"

namespace tightfit::test {

/// 3D point on the panel of a point in piece coordinates (m).
inline Vec3 piece_to_panel(const Layout& layout, const PieceMap& map, const Vec2& piece_point) {
  const TriangleLocator locator(layout.panels[map.panel].mesh.faces, map.flat);
  return panel_position(layout, map, locate_in_panel(locator, map, piece_point));
}

/// Piece coordinates of the point of the 3D panel closest to `p` (m), by a scan of the
/// panel's faces.
inline Vec2 panel_to_piece(const Layout& layout, const PieceMap& map, const Vec3& p) {
  const TriMesh& m = layout.panels[map.panel].mesh;
  double best = std::numeric_limits<double>::infinity();
  Vec2 result = Vec2::Zero();
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 w =
        closest_point_weights(p, m.vertices.row(m.faces(f, 0)), m.vertices.row(m.faces(f, 1)),
                              m.vertices.row(m.faces(f, 2)));
    Vec3 x = Vec3::Zero();
    Vec2 q = Vec2::Zero();
    for (int c = 0; c < 3; ++c) {
      x += w[c] * m.vertices.row(m.faces(f, c)).transpose();
      q += w[c] * map.flat.row(m.faces(f, c)).transpose();
    }
    const double d = (x - p).squaredNorm();
    if (d < best) {
      best = d;
      result = map.linear * q + map.offset;
    }
  }
  return result;
}

}  // namespace tightfit::test
