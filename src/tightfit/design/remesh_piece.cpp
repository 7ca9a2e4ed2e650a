#include "tightfit/design/remesh_piece.hpp"

#include <algorithm>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/boundary_resampling.hpp"
#include "tightfit/garment/piece_mesher.hpp"

namespace tightfit {
namespace {

/// The new boundary of one piece as it is emitted, loop by loop.
class BoundaryEmitter {
 public:
  BoundaryEmitter(const PatternPiece& old, ResampledPiece& out) : old_(old), out_(out) {
    out_.old_to_new.assign(static_cast<size_t>(old.rest.rows()), -1);
  }

  /// A new vertex at parameter t along the old edge from → to (t = 0: old vertex
  /// `from`); returns its index.
  int emit(int from, int to, double t) {
    VertexSource so;
    so.from = from;
    const int v = static_cast<int>(out_.sources.size());
    if (t == 0.0) {
      so.kind = VertexSource::kOldVertex;
      out_.old_to_new[static_cast<size_t>(from)] = v;
      points_.push_back(old_.rest.row(from).transpose());
    } else {
      so.kind = VertexSource::kEdge;
      so.to = to;
      so.t = t;
      points_.push_back((1.0 - t) * old_.rest.row(from).transpose() +
                        t * old_.rest.row(to).transpose());
    }
    out_.sources.push_back(so);
    return v;
  }

  /// The points emitted since the last call (k×2, m).
  Points2 take_polygon() {
    Points2 polygon = polygon_rows(points_);
    points_.clear();
    return polygon;
  }

 private:
  const PatternPiece& old_;
  ResampledPiece& out_;
  std::vector<Vec2> points_;
};

/// Emits one seam unit of piece p starting at loop position u: its range of the seam's
/// samples, in the loop's direction.
void emit_seam_unit(const Pattern& pattern, const BoundaryPlan& plan,
                    const std::vector<SeamResampling>& seams, int p, int u,
                    BoundaryEmitter& emitter, ResampledPiece& out) {
  const int nb = plan.loops[static_cast<size_t>(p)].size();
  const EdgeCover c = plan.cover[static_cast<size_t>(p)][static_cast<size_t>(u % nb)];
  const Seam& seam = pattern.seams[static_cast<size_t>(c.seam)];
  const SideRun& run = plan.sides[static_cast<size_t>(c.seam)][static_cast<size_t>(c.side)];
  const std::vector<int>& side_vertices = c.side == 0 ? seam.a.vertices : seam.b.vertices;
  const SeamResampling& resampling = seams[static_cast<size_t>(c.seam)];
  // Side index of the unit's start, and the seam range it begins (or, reversed, ends).
  const int iu = static_cast<int>(std::find(run.loop_pos.begin(), run.loop_pos.end(), u % nb) -
                                  run.loop_pos.begin());
  const std::vector<int>& split = plan.splits[static_cast<size_t>(c.seam)];
  const int r = static_cast<int>(std::lower_bound(split.begin(), split.end(), iu) - split.begin()) -
                (run.dir > 0 ? 0 : 1);
  if (r < 0 || r + 1 >= static_cast<int>(resampling.range_offset.size()))
    throw std::logic_error("remesh_piece: a seam unit does not start a seam range");
  const int k0 = resampling.range_offset[static_cast<size_t>(r)];
  const int k1 = resampling.range_offset[static_cast<size_t>(r + 1)];
  auto emit_sample = [&](int k) {
    const SeamSample& sm = resampling.samples[static_cast<size_t>(k)];
    const int from = side_vertices[static_cast<size_t>(sm.i)];
    const int to = sm.t > 0.0 ? side_vertices[static_cast<size_t>(sm.i + 1)] : from;
    out.seam_vertices.push_back({c.seam, c.side, k, emitter.emit(from, to, sm.t)});
  };
  if (run.dir > 0)
    for (int k = k0; k < k1; ++k) emit_sample(k);
  else
    for (int k = k1; k > k0; --k) emit_sample(k);
}

/// Emits the outer loop of piece p, unit by unit, in the old loop direction.
void emit_outer_loop(const Pattern& pattern, const BoundaryPlan& plan,
                     const std::vector<SeamResampling>& seams, int p, bool resample_free, double h,
                     BoundaryEmitter& emitter, ResampledPiece& out) {
  const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
  const BoundaryLoop& loop = plan.loops[static_cast<size_t>(p)];
  const std::vector<int>& starts = plan.unit_starts[static_cast<size_t>(p)];
  const int nu = plan.num_units(p);
  auto is_start = [&](int k) {
    return std::binary_search(starts.begin(), starts.end(), k % loop.size());
  };
  for (const LoopRun& unit : cut_run({starts.front(), loop.size()}, is_start)) {
    const int u = unit.first, w = unit.first + unit.count;
    if (plan.cover[static_cast<size_t>(p)][static_cast<size_t>(u % loop.size())].seam >= 0) {
      emit_seam_unit(pattern, plan, seams, p, u, emitter, out);
    } else if (!resample_free) {
      for (int k = u; k < w; ++k) emitter.emit(loop.at(k), loop.at(k + 1), 0.0);
    } else {
      std::vector<int> path;
      for (int k = u; k <= w; ++k) path.push_back(loop.at(k));
      const std::vector<double> cum = cumulative_lengths(piece.rest, path);
      for (const ArcPoint& at : sample_arc(cum, edge_count(cum.back(), h, min_edge_count(nu))))
        emitter.emit(loop.at(u + at.edge), loop.at(u + at.edge + 1), at.t);
    }
  }
}

/// Emits each hole rim of `piece`, resampled at the edge length h (m) by even 2D arc
/// length from its old first vertex; returns the new rims (new local vertices).
std::vector<std::vector<int>> emit_holes(const PatternPiece& piece, double h,
                                         BoundaryEmitter& emitter, std::vector<Points2>& polygons) {
  std::vector<std::vector<int>> rims;
  for (const std::vector<int>& hole : piece.holes) {
    if (hole.empty()) throw std::logic_error("remesh_piece: a hole without vertices");
    const int m = static_cast<int>(hole.size());
    std::vector<int> path = hole;
    path.push_back(hole.front());
    const std::vector<double> cum = cumulative_lengths(piece.rest, path);
    std::vector<int> rim;
    for (const ArcPoint& at : sample_arc(cum, edge_count(cum.back(), h, min_edge_count(1))))
      rim.push_back(emitter.emit(hole[static_cast<size_t>(at.edge % m)],
                                 hole[static_cast<size_t>((at.edge + 1) % m)], at.t));
    polygons.push_back(emitter.take_polygon());
    rims.push_back(std::move(rim));
  }
  return rims;
}

}  // namespace

ResampledPiece remesh_piece(const Pattern& pattern, int p, const BoundaryPlan& plan,
                            const std::vector<SeamResampling>& seams, bool resample_free,
                            double edge_length, int smoothing_iterations) {
  const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
  ResampledPiece out;
  BoundaryEmitter emitter(piece, out);
  emit_outer_loop(pattern, plan, seams, p, resample_free, edge_length, emitter, out);
  const Points2 polygon = emitter.take_polygon();
  std::vector<Points2> hole_polygons;
  out.piece.holes = emit_holes(piece, edge_length, emitter, hole_polygons);
  const auto num_loop_vertices = static_cast<Eigen::Index>(out.sources.size());
  PieceMesh mesh;
  try {
    mesh = mesh_piece(polygon, hole_polygons, edge_length, smoothing_iterations);
  } catch (const std::invalid_argument& e) {
    throw InputError("pattern piece " + piece.name,
                     std::string("the remeshed boundary cannot be meshed (") + e.what() + ")");
  }
  PatternPiece& np = out.piece;
  np.name = piece.name;
  np.grain = piece.grain;
  np.rest = std::move(mesh.vertices);
  np.triangles = std::move(mesh.triangles);
  for (Eigen::Index i = 0; i < polygon.rows(); ++i) np.boundary.push_back(static_cast<int>(i));
  for (int corner : piece.corners)
    if (corner >= 0 && corner < static_cast<int>(out.old_to_new.size()) &&
        out.old_to_new[static_cast<size_t>(corner)] >= 0)
      np.corners.push_back(out.old_to_new[static_cast<size_t>(corner)]);
  for (Eigen::Index v = num_loop_vertices; v < np.rest.rows(); ++v) {
    VertexSource so;
    so.kind = VertexSource::kRestPoint;
    so.q = np.rest.row(v).transpose();
    out.sources.push_back(so);
  }
  return out;
}

}  // namespace tightfit
