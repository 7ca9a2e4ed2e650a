#include "tightfit/design/embedding_transfer.hpp"

#include <stdexcept>

#include "tightfit/common/planar.hpp"
#include "tightfit/subdiv/limit_projector.hpp"

namespace tightfit {

EmbeddingTransfer::EmbeddingTransfer(const Garment& old_garment, const EmbeddedState& state,
                                     const Points3& positions, const LimitSurface& surface)
    : old_(old_garment),
      state_(state),
      positions_(positions),
      surface_(surface),
      control_(state.body.topRows(surface.num_control_vertices())) {
  for (const PatternPiece& piece : old_garment.pattern.pieces)
    locators_.emplace_back(piece.triangles, piece.rest);
  if (static_cast<int>(state.garment.size()) != old_garment.num_garment_vertices() ||
      positions.rows() != old_garment.num_garment_vertices())
    throw std::invalid_argument("EmbeddingTransfer: state or positions do not match the garment");
}

int EmbeddingTransfer::garment_vertex(int piece, int v) const {
  return old_.topology->pattern_to_garment[static_cast<size_t>(
      old_.topology->piece_offset[static_cast<size_t>(piece)] + v)];
}

SurfacePoint EmbeddingTransfer::project(const Vec3& point, int hint_garment_vertex) const {
  return refine_closest_point(surface_, control_, point,
                              state_.garment[static_cast<size_t>(hint_garment_vertex)]);
}

SurfacePoint EmbeddingTransfer::at_vertex(int piece, int v) const {
  return state_.garment[static_cast<size_t>(garment_vertex(piece, v))];
}

SurfacePoint EmbeddingTransfer::on_edge(int piece, int from, int to, double t) const {
  if (t == 0.0) return at_vertex(piece, from);
  const int a = garment_vertex(piece, from), b = garment_vertex(piece, to);
  const Vec3 x = (1.0 - t) * positions_.row(a).transpose() + t * positions_.row(b).transpose();
  return project(x, t < 0.5 ? a : b);
}

SurfacePoint EmbeddingTransfer::at_rest_point(int piece, const Vec2& q) const {
  const PatternPiece& pp = old_.pattern.pieces[static_cast<size_t>(piece)];
  const TriangleLocator& locator = locators_[static_cast<size_t>(piece)];
  if (locator.num_triangles() == 0)
    throw std::invalid_argument("EmbeddingTransfer: piece without triangles");
  int best = locator.containing(q, [&](int t) {
    return signed_area(pp.rest.row(pp.triangles(t, 0)), pp.rest.row(pp.triangles(t, 1)),
                       pp.rest.row(pp.triangles(t, 2))) > 0.0;
  });
  Vec3 best_w = Vec3::Zero();
  if (best >= 0) {
    best_w = locator.weights(best, q);
  } else {
    best = locator.nearest(q);
    best_w = locator.closest_weights(best, q);
  }
  int corner = 0;
  best_w.maxCoeff(&corner);
  if (best_w[corner] >= 1.0 - 1e-12) return at_vertex(piece, pp.triangles(best, corner));
  Vec3 x = Vec3::Zero();
  for (int c = 0; c < 3; ++c)
    x += best_w[c] * positions_.row(garment_vertex(piece, pp.triangles(best, c))).transpose();
  return project(x, garment_vertex(piece, pp.triangles(best, corner)));
}

}  // namespace tightfit
