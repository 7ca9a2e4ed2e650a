#include "tightfit/design/pattern_remesh.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "tightfit/common/planar.hpp"
#include "tightfit/design/remesh_boundary.hpp"
#include "tightfit/design/remesh_piece.hpp"

namespace tightfit {
namespace {

/// Per piece: whether it is in `pieces` (checked against the piece count and edge
/// lengths).
std::vector<bool> pieces_to_remesh(int np, const std::vector<int>& pieces,
                                   const std::vector<double>& edge_length) {
  if (static_cast<int>(edge_length.size()) != np)
    throw std::invalid_argument("remesh_garment: one edge length per piece is needed");
  std::vector<bool> remesh(static_cast<size_t>(np), false);
  for (int p : pieces) {
    if (p < 0 || p >= np) throw std::invalid_argument("remesh_garment: piece index out of range");
    if (!(edge_length[static_cast<size_t>(p)] > 0.0))
      throw std::invalid_argument("remesh_garment: edge lengths must be positive");
    remesh[static_cast<size_t>(p)] = true;
  }
  return remesh;
}

/// Per piece: whether its mesh changes, being remeshed or sewn to a remeshed piece.
std::vector<bool> changed_pieces(const Pattern& pattern, const std::vector<bool>& remesh) {
  std::vector<bool> changed = remesh;
  for (const Seam& seam : pattern.seams)
    if (remesh[static_cast<size_t>(seam.a.piece)] || remesh[static_cast<size_t>(seam.b.piece)])
      changed[static_cast<size_t>(seam.a.piece)] = changed[static_cast<size_t>(seam.b.piece)] =
          true;
  return changed;
}

/// A piece kept as it was: the same vertices, every old vertex its own new one.
ResampledPiece kept_piece(const PatternPiece& piece) {
  ResampledPiece out;
  out.piece = piece;
  for (Eigen::Index v = 0; v < piece.rest.rows(); ++v)
    out.old_to_new.push_back(static_cast<int>(v));
  return out;
}

/// The seams of the new pattern: the samples each remeshed piece emitted, the others
/// (sample ends and unchanged pieces) through the old → new vertex maps.
std::vector<Seam> remap_seams(const Pattern& pattern, const std::vector<SeamResampling>& seams,
                              const std::vector<ResampledPiece>& pieces) {
  std::vector<std::array<std::vector<int>, 2>> side(pattern.seams.size());
  for (size_t s = 0; s < pattern.seams.size(); ++s)
    for (std::vector<int>& list : side[s]) list.assign(seams[s].samples.size(), -1);
  for (const ResampledPiece& piece : pieces)
    for (const SeamVertex& sv : piece.seam_vertices)
      side[static_cast<size_t>(sv.seam)][static_cast<size_t>(sv.side)]
          [static_cast<size_t>(sv.sample)] = sv.vertex;
  std::vector<Seam> out;
  for (size_t s = 0; s < pattern.seams.size(); ++s) {
    const Seam& seam = pattern.seams[s];
    int k = 0;
    for (const SeamSide* old_side : {&seam.a, &seam.b}) {
      std::vector<int>& list = side[s][static_cast<size_t>(k++)];
      const std::vector<int>& o2n = pieces[static_cast<size_t>(old_side->piece)].old_to_new;
      for (size_t i = 0; i < list.size(); ++i) {
        if (list[i] >= 0) continue;
        const SeamSample& sm = seams[s].samples[i];
        if (sm.t != 0.0) throw std::logic_error("remesh_garment: a seam sample was not emitted");
        list[i] = o2n[static_cast<size_t>(old_side->vertices[static_cast<size_t>(sm.i)])];
        if (list[i] < 0) throw std::logic_error("remesh_garment: a seam vertex was lost");
      }
    }
    Seam next;
    next.name = seam.name;
    next.a = {seam.a.piece, side[s][0]};
    next.b = {seam.b.piece, side[s][1]};
    out.push_back(std::move(next));
  }
  return out;
}

/// A pinned boundary of a changed piece in the new piece's vertices: a hole rim's new
/// rim, a whole loop the whole new loop, an open run from its new first to its new last
/// vertex.
PinnedBoundary remap_pinned(const PinnedBoundary& pin, const Pattern& pattern,
                            const BoundaryPlan& plan, const ResampledPiece& piece) {
  PinnedBoundary out = pin;
  out.vertices.clear();
  const PatternPiece& old_piece = pattern.pieces[static_cast<size_t>(pin.piece)];
  const int nb = static_cast<int>(piece.piece.boundary.size());
  if (plan.on_hole(pin)) {
    for (size_t h = 0; h < old_piece.holes.size(); ++h)
      if (std::find(old_piece.holes[h].begin(), old_piece.holes[h].end(), pin.vertices.front()) !=
          old_piece.holes[h].end())
        out.vertices = piece.piece.holes[h];
  } else if (static_cast<int>(pin.vertices.size()) ==
             plan.loops[static_cast<size_t>(pin.piece)].size()) {
    for (int i = 0; i < nb; ++i) out.vertices.push_back(i);
  } else {
    const SideRun run = side_run(plan.loops[static_cast<size_t>(pin.piece)],
                                 SeamSide{pin.piece, pin.vertices}, old_piece, "pinned boundary");
    const int first = piece.old_to_new[static_cast<size_t>(pin.vertices.front())];
    const int last = piece.old_to_new[static_cast<size_t>(pin.vertices.back())];
    if (first < 0 || last < 0) throw std::logic_error("remesh_garment: a pinned end was lost");
    for (int i = first;; i = (i + run.dir + nb) % nb) {
      out.vertices.push_back(i);
      if (i == last) break;
    }
  }
  return out;
}

/// The surface point of every garment vertex of `g` (the welded new pattern), from the
/// first pattern vertex welded into it: an unchanged piece's from its old vertex, a
/// remeshed piece's from its source in the old piece.
std::vector<SurfacePoint> transfer_embedding(const Garment& g,
                                             const std::vector<ResampledPiece>& pieces,
                                             const std::vector<bool>& unchanged,
                                             const EmbeddingTransfer& transfer) {
  std::vector<bool> done(static_cast<size_t>(g.num_garment_vertices()), false);
  std::vector<SurfacePoint> embedding(static_cast<size_t>(g.num_garment_vertices()));
  for (int p = 0; p < static_cast<int>(pieces.size()); ++p) {
    const int n = static_cast<int>(g.pattern.pieces[static_cast<size_t>(p)].rest.rows());
    for (int v = 0; v < n; ++v) {
      const int gv = g.topology->pattern_to_garment[static_cast<size_t>(
          g.topology->piece_offset[static_cast<size_t>(p)] + v)];
      if (done[static_cast<size_t>(gv)]) continue;
      done[static_cast<size_t>(gv)] = true;
      SurfacePoint& sp = embedding[static_cast<size_t>(gv)];
      if (unchanged[static_cast<size_t>(p)]) {
        sp = transfer.at_vertex(p, v);
        continue;
      }
      const VertexSource& so = pieces[static_cast<size_t>(p)].sources[static_cast<size_t>(v)];
      switch (so.kind) {
        case VertexSource::kOldVertex:
          sp = transfer.at_vertex(p, so.from);
          break;
        case VertexSource::kEdge:
          sp = transfer.on_edge(p, so.from, so.to, so.t);
          break;
        case VertexSource::kRestPoint:
          sp = transfer.at_rest_point(p, so.q);
          break;
      }
    }
  }
  return embedding;
}

}  // namespace

PieceQuality piece_quality(const PatternPiece& piece) {
  PieceQuality q;
  q.min_angle_deg = 180.0;
  q.min_area = std::numeric_limits<double>::infinity();
  // Angles at a sharp corner of the outline (interior angle below 60°) are bounded by the
  // corner, not by the mesh: no remeshing raises them, so they do not count.
  const Eigen::Index nv = piece.rest.rows();
  std::vector<double> corner_angle(static_cast<size_t>(nv), 0.0);
  std::vector<std::array<double, 3>> angles(static_cast<size_t>(piece.triangles.rows()));
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    const Vec2 p[3] = {piece.rest.row(piece.triangles(t, 0)), piece.rest.row(piece.triangles(t, 1)),
                       piece.rest.row(piece.triangles(t, 2))};
    for (int c = 0; c < 3; ++c) {
      angles[static_cast<size_t>(t)][static_cast<size_t>(c)] =
          angle_between_deg(p[(c + 1) % 3] - p[c], p[(c + 2) % 3] - p[c]);
      corner_angle[static_cast<size_t>(piece.triangles(t, c))] +=
          angles[static_cast<size_t>(t)][static_cast<size_t>(c)];
    }
  }
  std::vector<char> sharp_corner(static_cast<size_t>(nv), 0);
  for (int v : piece.boundary_vertices())
    sharp_corner[static_cast<size_t>(v)] = corner_angle[static_cast<size_t>(v)] < 60.0 ? 1 : 0;
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    const Vec2 p[3] = {piece.rest.row(piece.triangles(t, 0)), piece.rest.row(piece.triangles(t, 1)),
                       piece.rest.row(piece.triangles(t, 2))};
    const double area = signed_area(p[0], p[1], p[2]);
    q.min_area = std::min(q.min_area, area);
    if (!(area > 0.0)) {
      q.min_angle_deg = 0.0;
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (!sharp_corner[static_cast<size_t>(piece.triangles(t, c))])
        q.min_angle_deg =
            std::min(q.min_angle_deg, angles[static_cast<size_t>(t)][static_cast<size_t>(c)]);
  }
  if (piece.triangles.rows() == 0) q.min_area = 0.0;
  return q;
}

double mean_edge_length(const PatternPiece& piece) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      sum +=
          (piece.rest.row(piece.triangles(t, c)) - piece.rest.row(piece.triangles(t, (c + 1) % 3)))
              .norm();
  return piece.triangles.rows() > 0 ? sum / (3.0 * static_cast<double>(piece.triangles.rows()))
                                    : 0.0;
}

PatternRemeshResult remesh_garment(const Garment& old_garment, const EmbeddedState& state,
                                   const Points3& positions, const LimitSurface& surface,
                                   const std::vector<int>& pieces,
                                   const std::vector<double>& edge_length,
                                   int smoothing_iterations) {
  const Pattern& pattern = old_garment.pattern;
  const int np = static_cast<int>(pattern.pieces.size());
  const std::vector<bool> remesh = pieces_to_remesh(np, pieces, edge_length);
  const BoundaryPlan plan = plan_boundary(pattern);
  const std::vector<SeamResampling> seams =
      resample_seams(old_garment, positions, plan, remesh, edge_length);
  const std::vector<bool> changed = changed_pieces(pattern, remesh);

  PatternRemeshResult result;
  std::vector<ResampledPiece> next_pieces;
  for (int p = 0; p < np; ++p) {
    const size_t k = static_cast<size_t>(p);
    result.unchanged.push_back(!changed[k]);
    if (!changed[k]) {
      next_pieces.push_back(kept_piece(pattern.pieces[k]));
      continue;
    }
    result.remeshed.push_back(p);
    next_pieces.push_back(
        remesh_piece(pattern, p, plan, seams, remesh[k], edge_length[k], smoothing_iterations));
  }

  Pattern next;
  next.seams = remap_seams(pattern, seams, next_pieces);
  for (const PinnedBoundary& pin : pattern.pinned)
    next.pinned.push_back(
        changed[static_cast<size_t>(pin.piece)] && !pin.vertices.empty()
            ? remap_pinned(pin, pattern, plan, next_pieces[static_cast<size_t>(pin.piece)])
            : pin);
  for (const ResampledPiece& piece : next_pieces) next.pieces.push_back(piece.piece);

  result.garment = weld_pattern(std::move(next));
  const EmbeddingTransfer transfer(old_garment, state, positions, surface);
  result.garment.embedding =
      transfer_embedding(result.garment, next_pieces, result.unchanged, transfer);
  result.state.garment = result.garment.embedding;
  result.state.body = state.body;
  return result;
}

}  // namespace tightfit
