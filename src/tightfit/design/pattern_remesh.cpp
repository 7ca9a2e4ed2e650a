#include "tightfit/design/pattern_remesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/garment/piece_mesher.hpp"
#include "tightfit/garment/triangle_geometry.hpp"
#include "tightfit/subdiv/limit_projector.hpp"

namespace tightfit {
namespace {

std::string piece_source(const PatternPiece& piece) { return "pattern piece " + piece.name; }

/// Where a new pattern vertex comes from.
struct Source {
  enum Kind { kOldVertex, kEdge, kRestPoint } kind = kOldVertex;
  int from = -1;  ///< old local vertex (kOldVertex, kEdge)
  int to = -1;    ///< old local vertex (kEdge)
  double t = 0.0;
  Vec2 q = Vec2::Zero();  ///< rest point (kRestPoint)
};

/// A sample of a seam in its index space: between side vertices i and i+1 at t ∈ [0,1).
struct SeamSample {
  int i = 0;
  double t = 0.0;
};

/// One seam side as a run of the boundary loop.
struct SideRun {
  int piece = -1;
  int dir = 1;                ///< +1: side order = loop order, −1: reversed
  std::vector<int> loop_pos;  ///< loop position of every side vertex
};

/// A piece's boundary loop with look-ups.
struct Loop {
  std::vector<int> vertices;  ///< the boundary loop (local vertex indices)
  std::vector<int> pos;       ///< local vertex → loop position, −1 off the loop
  int size() const { return static_cast<int>(vertices.size()); }
  int at(int k) const { return vertices[static_cast<size_t>(((k % size()) + size()) % size())]; }
};

SideRun side_run(const Loop& loop, const SeamSide& side, const PatternPiece& piece,
                 const std::string& what) {
  SideRun run;
  run.piece = side.piece;
  const int nb = loop.size();
  for (int v : side.vertices) {
    const int k = v >= 0 && v < static_cast<int>(loop.pos.size()) ? loop.pos[v] : -1;
    if (k < 0)
      throw InputError(piece_source(piece),
                       what + " has vertex " + std::to_string(v) + " off the boundary loop");
    run.loop_pos.push_back(k);
  }
  if (run.loop_pos.size() >= 2) {
    run.dir = (run.loop_pos[1] - run.loop_pos[0] + nb) % nb == 1 ? 1 : -1;
    for (size_t i = 0; i + 1 < run.loop_pos.size(); ++i)
      if (((run.loop_pos[i + 1] - run.loop_pos[i]) % nb + nb) % nb != (run.dir + nb) % nb)
        throw InputError(piece_source(piece),
                         what + " is not a run of consecutive boundary vertices");
  }
  return run;
}

/// Loop length (m, 2D rest) from loop position a to b going forward.
double loop_length(const PatternPiece& piece, const Loop& loop, int a, int b) {
  double len = 0.0;
  for (int k = a; k < b; ++k)
    len += (piece.rest.row(loop.at(k + 1)) - piece.rest.row(loop.at(k))).norm();
  return len;
}

/// Edge counts below which a unit may not go: a piece boundary needs >= 3 vertices.
int min_count(int units) { return units == 1 ? 3 : (units == 2 ? 2 : 1); }

/// Index (e, t) of the arc-length target along cumulative lengths `cum` (e from 0).
std::pair<int, double> locate_arc(const std::vector<double>& cum, double target) {
  int e = 0;
  const int edges = static_cast<int>(cum.size()) - 1;
  while (e + 1 < edges && cum[static_cast<size_t>(e + 1)] <= target) ++e;
  const double len = cum[static_cast<size_t>(e + 1)] - cum[static_cast<size_t>(e)];
  double t = len > 0.0 ? std::clamp((target - cum[static_cast<size_t>(e)]) / len, 0.0, 1.0) : 0.0;
  if (t >= 1.0) return {e + 1, 0.0};
  return {e, t};
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

// ----------------------------------------------------------------------------------

EmbeddingTransfer::EmbeddingTransfer(const Garment& old_garment, const EmbeddedState& state,
                                     const Points3& positions, const LimitSurface& surface)
    : old_(old_garment),
      state_(state),
      positions_(positions),
      surface_(surface),
      control_(state.body.topRows(surface.num_control_vertices())) {
  if (static_cast<int>(state.garment.size()) != old_garment.num_garment_vertices ||
      positions.rows() != old_garment.num_garment_vertices)
    throw std::invalid_argument("EmbeddingTransfer: state or positions do not match the garment");
}

int EmbeddingTransfer::garment_vertex(int piece, int v) const {
  return old_
      .pattern_to_garment[static_cast<size_t>(old_.piece_offset[static_cast<size_t>(piece)] + v)];
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
  int best = -1;
  Vec3 best_w = Vec3::Zero();
  double best_d = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < pp.triangles.rows(); ++t) {
    const Vec2 a = pp.rest.row(pp.triangles(t, 0)), b = pp.rest.row(pp.triangles(t, 1)),
               c = pp.rest.row(pp.triangles(t, 2));
    const Vec3 w = barycentric_2d(q, a, b, c);
    if (w.minCoeff() >= -1e-12 && signed_area(a, b, c) > 0.0) {
      best = static_cast<int>(t);
      best_w = w;
      break;
    }
    const Vec3 wc = closest_point_weights_2d(q, a, b, c);
    const double d = (wc[0] * a + wc[1] * b + wc[2] * c - q).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(t);
      best_w = wc;
    }
  }
  if (best < 0) throw std::invalid_argument("EmbeddingTransfer: piece without triangles");
  int corner = 0;
  best_w.maxCoeff(&corner);
  if (best_w[corner] >= 1.0 - 1e-12) return at_vertex(piece, pp.triangles(best, corner));
  Vec3 x = Vec3::Zero();
  for (int c = 0; c < 3; ++c)
    x += best_w[c] * positions_.row(garment_vertex(piece, pp.triangles(best, c))).transpose();
  return project(x, garment_vertex(piece, pp.triangles(best, corner)));
}

// ----------------------------------------------------------------------------------

PatternRemeshResult remesh_garment(const Garment& old_garment, const EmbeddedState& state,
                                   const Points3& positions, const LimitSurface& surface,
                                   const std::vector<int>& pieces,
                                   const std::vector<double>& edge_length,
                                   int smoothing_iterations) {
  const Pattern& pattern = old_garment.pattern;
  const int np = static_cast<int>(pattern.pieces.size());
  if (static_cast<int>(edge_length.size()) != np)
    throw std::invalid_argument("remesh_garment: one edge length per piece is needed");
  std::vector<bool> remesh(static_cast<size_t>(np), false);
  for (int p : pieces) {
    if (p < 0 || p >= np) throw std::invalid_argument("remesh_garment: piece index out of range");
    if (!(edge_length[static_cast<size_t>(p)] > 0.0))
      throw std::invalid_argument("remesh_garment: edge lengths must be positive");
    remesh[static_cast<size_t>(p)] = true;
  }

  // Boundary loops and break points (corners, ends of seam sides and open pinned runs).
  std::vector<Loop> loops(static_cast<size_t>(np));
  std::vector<std::set<int>> breaks(static_cast<size_t>(np));
  for (int p = 0; p < np; ++p) {
    const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
    Loop& loop = loops[static_cast<size_t>(p)];
    loop.vertices = piece.boundary;
    loop.pos.assign(static_cast<size_t>(piece.rest.rows()), -1);
    for (int k = 0; k < loop.size(); ++k)
      loop.pos[static_cast<size_t>(loop.vertices[static_cast<size_t>(k)])] = k;
    for (int c : piece.corners)
      if (c >= 0 && c < static_cast<int>(loop.pos.size()) && loop.pos[static_cast<size_t>(c)] >= 0)
        breaks[static_cast<size_t>(p)].insert(loop.pos[static_cast<size_t>(c)]);
  }
  const int ns = static_cast<int>(pattern.seams.size());
  std::vector<std::array<SideRun, 2>> sides(static_cast<size_t>(ns));
  for (int s = 0; s < ns; ++s) {
    const Seam& seam = pattern.seams[static_cast<size_t>(s)];
    int k = 0;
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      const PatternPiece& piece = pattern.pieces[static_cast<size_t>(side->piece)];
      SideRun run = side_run(loops[static_cast<size_t>(side->piece)], *side, piece,
                             "seam \"" + seam.name + "\"");
      breaks[static_cast<size_t>(side->piece)].insert(run.loop_pos.front());
      breaks[static_cast<size_t>(side->piece)].insert(run.loop_pos.back());
      sides[static_cast<size_t>(s)][static_cast<size_t>(k++)] = std::move(run);
    }
    if (seam.a.vertices.size() != seam.b.vertices.size() || seam.a.vertices.size() < 2)
      throw InputError("pattern",
                       "seam \"" + seam.name + "\" has sides of unequal or too few vertices");
  }
  // A pinned boundary on a hole's rim (its first vertex is not on the outer loop).
  auto on_hole = [&](const PinnedBoundary& pin) {
    const Loop& loop = loops[static_cast<size_t>(pin.piece)];
    return !pin.vertices.empty() && loop.pos[static_cast<size_t>(pin.vertices.front())] < 0;
  };
  for (const PinnedBoundary& pin : pattern.pinned) {
    const Loop& loop = loops[static_cast<size_t>(pin.piece)];
    if (static_cast<int>(pin.vertices.size()) == loop.size() || pin.vertices.empty() ||
        on_hole(pin))
      continue;
    const PatternPiece& piece = pattern.pieces[static_cast<size_t>(pin.piece)];
    const SideRun run = side_run(loop, SeamSide{pin.piece, pin.vertices}, piece,
                                 "pinned boundary \"" + pin.name + "\"");
    breaks[static_cast<size_t>(pin.piece)].insert(run.loop_pos.front());
    breaks[static_cast<size_t>(pin.piece)].insert(run.loop_pos.back());
  }
  for (int p = 0; p < np; ++p)
    if (breaks[static_cast<size_t>(p)].empty()) breaks[static_cast<size_t>(p)].insert(0);

  // Seam split indices, unit boundaries per piece, and which loop edge a side covers.
  struct Cover {
    int seam = -1, side = -1;
  };
  std::vector<std::vector<Cover>> cover(static_cast<size_t>(np));
  for (int p = 0; p < np; ++p)
    cover[static_cast<size_t>(p)].assign(static_cast<size_t>(loops[static_cast<size_t>(p)].size()),
                                         {});
  std::vector<std::vector<int>> splits(static_cast<size_t>(ns));
  std::vector<std::set<int>> unit_bounds = breaks;
  for (int s = 0; s < ns; ++s) {
    std::set<int> split;
    for (int k = 0; k < 2; ++k) {
      const SideRun& run = sides[static_cast<size_t>(s)][static_cast<size_t>(k)];
      const int m = static_cast<int>(run.loop_pos.size()) - 1;
      for (int i = 0; i <= m; ++i)
        if (breaks[static_cast<size_t>(run.piece)].count(run.loop_pos[static_cast<size_t>(i)]))
          split.insert(i);
      for (int i = 0; i < m; ++i) {
        const int edge = run.dir > 0 ? run.loop_pos[static_cast<size_t>(i)]
                                     : run.loop_pos[static_cast<size_t>(i + 1)];
        Cover& c = cover[static_cast<size_t>(run.piece)][static_cast<size_t>(edge)];
        if (c.seam >= 0)
          throw InputError(piece_source(pattern.pieces[static_cast<size_t>(run.piece)]),
                           "a boundary edge is on two seam sides");
        c = {s, k};
      }
    }
    splits[static_cast<size_t>(s)].assign(split.begin(), split.end());
    for (int k = 0; k < 2; ++k) {
      const SideRun& run = sides[static_cast<size_t>(s)][static_cast<size_t>(k)];
      for (int i : splits[static_cast<size_t>(s)])
        unit_bounds[static_cast<size_t>(run.piece)].insert(run.loop_pos[static_cast<size_t>(i)]);
    }
  }
  auto units_of = [&](int p) {
    return static_cast<int>(unit_bounds[static_cast<size_t>(p)].size());
  };

  // Seam samples: per seam, the samples of all sub-ranges concatenated (shared ends once).
  std::vector<std::vector<SeamSample>> seam_samples(static_cast<size_t>(ns));
  std::vector<std::vector<int>> range_offset(static_cast<size_t>(ns));  // per sub-range
  std::vector<bool> changed = remesh;
  for (int s = 0; s < ns; ++s) {
    const Seam& seam = pattern.seams[static_cast<size_t>(s)];
    const std::vector<int>& split = splits[static_cast<size_t>(s)];
    const int pa = seam.a.piece, pb = seam.b.piece;
    const bool resample = remesh[static_cast<size_t>(pa)] || remesh[static_cast<size_t>(pb)];
    if (resample) changed[static_cast<size_t>(pa)] = changed[static_cast<size_t>(pb)] = true;
    std::vector<SeamSample>& out = seam_samples[static_cast<size_t>(s)];
    for (size_t r = 0; r + 1 < split.size(); ++r) {
      const int i0 = split[r], i1 = split[r + 1];
      range_offset[static_cast<size_t>(s)].push_back(static_cast<int>(out.size()));
      if (!resample) {
        for (int i = i0; i < i1; ++i) out.push_back({i, 0.0});
        continue;
      }
      double la = 0.0, lb = 0.0;
      std::vector<double> cum(1, 0.0);
      const PatternPiece& A = pattern.pieces[static_cast<size_t>(pa)];
      const PatternPiece& B = pattern.pieces[static_cast<size_t>(pb)];
      for (int i = i0; i < i1; ++i) {
        const int a0 = seam.a.vertices[static_cast<size_t>(i)],
                  a1 = seam.a.vertices[static_cast<size_t>(i + 1)];
        const int b0 = seam.b.vertices[static_cast<size_t>(i)],
                  b1 = seam.b.vertices[static_cast<size_t>(i + 1)];
        la += (A.rest.row(a1) - A.rest.row(a0)).norm();
        lb += (B.rest.row(b1) - B.rest.row(b0)).norm();
        const int g0 = old_garment.pattern_to_garment[static_cast<size_t>(
            old_garment.piece_offset[static_cast<size_t>(pa)] + a0)];
        const int g1 = old_garment.pattern_to_garment[static_cast<size_t>(
            old_garment.piece_offset[static_cast<size_t>(pa)] + a1)];
        cum.push_back(cum.back() + (positions.row(g1) - positions.row(g0)).norm());
      }
      const double h =
          0.5 * (edge_length[static_cast<size_t>(pa)] + edge_length[static_cast<size_t>(pb)]);
      const int n = std::max({min_count(units_of(pa)), min_count(units_of(pb)),
                              static_cast<int>(std::lround(0.5 * (la + lb) / h))});
      out.push_back({i0, 0.0});
      for (int k = 1; k < n; ++k) {
        const auto [e, t] = locate_arc(cum, cum.back() * k / n);
        out.push_back({i0 + e, t});
      }
    }
    range_offset[static_cast<size_t>(s)].push_back(static_cast<int>(out.size()));
    out.push_back({split.back(), 0.0});
  }

  // New boundary loops, piece by piece, in the old loop direction.
  PatternRemeshResult result;
  result.unchanged.assign(static_cast<size_t>(np), false);
  Pattern next;
  next.pieces.resize(static_cast<size_t>(np));
  std::vector<std::vector<Source>> sources(static_cast<size_t>(np));
  std::vector<std::vector<int>> old_to_new(static_cast<size_t>(np));
  // new side vertices per seam and side (−1 until known)
  std::vector<std::array<std::vector<int>, 2>> new_side(static_cast<size_t>(ns));
  for (int s = 0; s < ns; ++s)
    for (int k = 0; k < 2; ++k)
      new_side[static_cast<size_t>(s)][static_cast<size_t>(k)].assign(
          seam_samples[static_cast<size_t>(s)].size(), -1);

  for (int p = 0; p < np; ++p) {
    const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
    PatternPiece& out = next.pieces[static_cast<size_t>(p)];
    std::vector<int>& o2n = old_to_new[static_cast<size_t>(p)];
    o2n.assign(static_cast<size_t>(piece.rest.rows()), -1);
    if (!changed[static_cast<size_t>(p)]) {
      out = piece;
      result.unchanged[static_cast<size_t>(p)] = true;
      for (Eigen::Index v = 0; v < piece.rest.rows(); ++v)
        o2n[static_cast<size_t>(v)] = static_cast<int>(v);
      continue;
    }
    result.remeshed.push_back(p);
    const Loop& loop = loops[static_cast<size_t>(p)];
    const int nb = loop.size();
    const double h = edge_length[static_cast<size_t>(p)];
    std::vector<Source>& src = sources[static_cast<size_t>(p)];
    std::vector<Vec2> boundary;
    auto emit_edge = [&](int from, int to, double t) {
      Source so;
      if (t == 0.0) {
        so.kind = Source::kOldVertex;
        so.from = from;
        o2n[static_cast<size_t>(from)] = static_cast<int>(src.size());
        boundary.push_back(piece.rest.row(from).transpose());
      } else {
        so.kind = Source::kEdge;
        so.from = from;
        so.to = to;
        so.t = t;
        boundary.push_back((1.0 - t) * piece.rest.row(from).transpose() +
                           t * piece.rest.row(to).transpose());
      }
      src.push_back(so);
    };
    const std::vector<int> ub(unit_bounds[static_cast<size_t>(p)].begin(),
                              unit_bounds[static_cast<size_t>(p)].end());
    const int nu = static_cast<int>(ub.size());
    for (int j = 0; j < nu; ++j) {
      const int u = ub[static_cast<size_t>(j)];
      const int w = j + 1 < nu ? ub[static_cast<size_t>(j + 1)] : ub[0] + nb;
      const Cover c = cover[static_cast<size_t>(p)][static_cast<size_t>(u)];
      if (c.seam < 0) {  // a free unit
        if (!remesh[static_cast<size_t>(p)]) {
          for (int k = u; k < w; ++k) emit_edge(loop.at(k), loop.at(k + 1), 0.0);
          continue;
        }
        std::vector<double> cum(1, 0.0);
        for (int k = u; k < w; ++k) cum.push_back(cum.back() + loop_length(piece, loop, k, k + 1));
        const int n = std::max(min_count(nu), static_cast<int>(std::lround(cum.back() / h)));
        for (int k = 0; k < n; ++k) {
          const auto [e, t] = locate_arc(cum, cum.back() * k / n);
          emit_edge(loop.at(u + e), loop.at(u + e + 1), t);
        }
        continue;
      }
      // A seam unit: one sub-range of the seam's index space.
      const Seam& seam = pattern.seams[static_cast<size_t>(c.seam)];
      const SideRun& run = sides[static_cast<size_t>(c.seam)][static_cast<size_t>(c.side)];
      const std::vector<int>& side_vertices = c.side == 0 ? seam.a.vertices : seam.b.vertices;
      const std::vector<SeamSample>& samples = seam_samples[static_cast<size_t>(c.seam)];
      std::vector<int>& ns_list =
          new_side[static_cast<size_t>(c.seam)][static_cast<size_t>(c.side)];
      // Side index of the unit's start.
      const int iu = static_cast<int>(std::find(run.loop_pos.begin(), run.loop_pos.end(), u % nb) -
                                      run.loop_pos.begin());
      const std::vector<int>& split = splits[static_cast<size_t>(c.seam)];
      const std::vector<int>& off = range_offset[static_cast<size_t>(c.seam)];
      const int r =
          static_cast<int>(std::lower_bound(split.begin(), split.end(), iu) - split.begin()) -
          (run.dir > 0 ? 0 : 1);
      const int k0 = off[static_cast<size_t>(r)], k1 = off[static_cast<size_t>(r + 1)];
      auto emit_sample = [&](int K) {
        const SeamSample& sm = samples[static_cast<size_t>(K)];
        const int from = side_vertices[static_cast<size_t>(sm.i)];
        const int to = sm.t > 0.0 ? side_vertices[static_cast<size_t>(sm.i + 1)] : from;
        ns_list[static_cast<size_t>(K)] = static_cast<int>(src.size());
        emit_edge(from, to, sm.t);
      };
      if (run.dir > 0)
        for (int K = k0; K < k1; ++K) emit_sample(K);
      else
        for (int K = k1; K > k0; --K) emit_sample(K);
    }

    Points2 polygon(static_cast<Eigen::Index>(boundary.size()), 2);
    for (size_t i = 0; i < boundary.size(); ++i)
      polygon.row(static_cast<Eigen::Index>(i)) = boundary[i].transpose();
    // Holes: each rim resampled at the edge length by even 2D arc length, starting at its
    // old first vertex; they follow the outer loop in the old order.
    std::vector<Points2> hole_polygons;
    out.holes.clear();
    for (const std::vector<int>& hole : piece.holes) {
      const int m = static_cast<int>(hole.size());
      std::vector<double> cum(1, 0.0);
      for (int e = 0; e < m; ++e)
        cum.push_back(cum.back() + (piece.rest.row(hole[static_cast<size_t>((e + 1) % m)]) -
                                    piece.rest.row(hole[static_cast<size_t>(e)]))
                                       .norm());
      const int n = std::max(3, static_cast<int>(std::lround(cum.back() / h)));
      Points2 hole_polygon(n, 2);
      std::vector<int> new_hole;
      for (int k = 0; k < n; ++k) {
        const auto [e, t] = locate_arc(cum, cum.back() * k / n);
        const int from = hole[static_cast<size_t>(e % m)],
                  to = hole[static_cast<size_t>((e + 1) % m)];
        Source so;
        so.from = from;
        if (t == 0.0) {
          so.kind = Source::kOldVertex;
          o2n[static_cast<size_t>(from)] = static_cast<int>(src.size());
        } else {
          so.kind = Source::kEdge;
          so.to = to;
          so.t = t;
        }
        hole_polygon.row(k) = (1.0 - t) * piece.rest.row(from) + t * piece.rest.row(to);
        new_hole.push_back(static_cast<int>(src.size()));
        src.push_back(so);
      }
      hole_polygons.push_back(std::move(hole_polygon));
      out.holes.push_back(std::move(new_hole));
    }
    const auto num_loop_vertices = static_cast<Eigen::Index>(src.size());
    PieceMesh mesh;
    try {
      mesh = mesh_piece(polygon, hole_polygons, h, smoothing_iterations);
    } catch (const std::invalid_argument& e) {
      throw InputError(piece_source(piece),
                       std::string("the remeshed boundary cannot be meshed (") + e.what() + ")");
    }
    out.name = piece.name;
    out.grain = piece.grain;
    out.rest = std::move(mesh.vertices);
    out.triangles = std::move(mesh.triangles);
    out.boundary.clear();
    for (Eigen::Index i = 0; i < polygon.rows(); ++i) out.boundary.push_back(static_cast<int>(i));
    out.corners.clear();
    for (int corner : piece.corners)
      if (corner >= 0 && corner < static_cast<int>(o2n.size()) &&
          o2n[static_cast<size_t>(corner)] >= 0)
        out.corners.push_back(o2n[static_cast<size_t>(corner)]);
    for (Eigen::Index v = num_loop_vertices; v < out.rest.rows(); ++v) {
      Source so;
      so.kind = Source::kRestPoint;
      so.q = out.rest.row(v).transpose();
      src.push_back(so);
    }
  }

  // Seams: sample ends (old vertices) and unchanged pieces through the old→new maps.
  for (int s = 0; s < ns; ++s) {
    const Seam& seam = pattern.seams[static_cast<size_t>(s)];
    Seam out;
    out.name = seam.name;
    int k = 0;
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      std::vector<int>& list = new_side[static_cast<size_t>(s)][static_cast<size_t>(k++)];
      const std::vector<int>& o2n = old_to_new[static_cast<size_t>(side->piece)];
      for (size_t K = 0; K < list.size(); ++K) {
        if (list[K] >= 0) continue;
        const SeamSample& sm = seam_samples[static_cast<size_t>(s)][K];
        if (sm.t != 0.0) throw std::logic_error("remesh_garment: a seam sample was not emitted");
        list[K] = o2n[static_cast<size_t>(side->vertices[static_cast<size_t>(sm.i)])];
        if (list[K] < 0) throw std::logic_error("remesh_garment: a seam vertex was lost");
      }
    }
    out.a = {seam.a.piece, new_side[static_cast<size_t>(s)][0]};
    out.b = {seam.b.piece, new_side[static_cast<size_t>(s)][1]};
    next.seams.push_back(std::move(out));
  }

  // Pinned boundaries.
  for (const PinnedBoundary& pin : pattern.pinned) {
    PinnedBoundary out = pin;
    if (changed[static_cast<size_t>(pin.piece)] && !pin.vertices.empty()) {
      const std::vector<int>& o2n = old_to_new[static_cast<size_t>(pin.piece)];
      const int nb = static_cast<int>(next.pieces[static_cast<size_t>(pin.piece)].boundary.size());
      out.vertices.clear();
      if (on_hole(pin)) {
        const PatternPiece& old_piece = pattern.pieces[static_cast<size_t>(pin.piece)];
        for (size_t h = 0; h < old_piece.holes.size(); ++h)
          if (std::find(old_piece.holes[h].begin(), old_piece.holes[h].end(),
                        pin.vertices.front()) != old_piece.holes[h].end())
            out.vertices = next.pieces[static_cast<size_t>(pin.piece)].holes[h];
      } else if (static_cast<int>(pin.vertices.size()) ==
                 loops[static_cast<size_t>(pin.piece)].size()) {
        for (int i = 0; i < nb; ++i) out.vertices.push_back(i);
      } else {
        const SideRun run =
            side_run(loops[static_cast<size_t>(pin.piece)], SeamSide{pin.piece, pin.vertices},
                     pattern.pieces[static_cast<size_t>(pin.piece)], "pinned boundary");
        const int first = o2n[static_cast<size_t>(pin.vertices.front())];
        const int last = o2n[static_cast<size_t>(pin.vertices.back())];
        if (first < 0 || last < 0) throw std::logic_error("remesh_garment: a pinned end was lost");
        for (int i = first;; i = (i + run.dir + nb) % nb) {
          out.vertices.push_back(i);
          if (i == last) break;
        }
      }
    }
    next.pinned.push_back(std::move(out));
  }

  // Weld and transfer the embedding.
  result.garment = weld_pattern(std::move(next));
  Garment& g = result.garment;
  const EmbeddingTransfer transfer(old_garment, state, positions, surface);
  std::vector<bool> done(static_cast<size_t>(g.num_garment_vertices), false);
  g.embedding.assign(static_cast<size_t>(g.num_garment_vertices), SurfacePoint{});
  for (int p = 0; p < np; ++p) {
    const int n = static_cast<int>(g.pattern.pieces[static_cast<size_t>(p)].rest.rows());
    for (int v = 0; v < n; ++v) {
      const int gv =
          g.pattern_to_garment[static_cast<size_t>(g.piece_offset[static_cast<size_t>(p)] + v)];
      if (done[static_cast<size_t>(gv)]) continue;
      done[static_cast<size_t>(gv)] = true;
      SurfacePoint& sp = g.embedding[static_cast<size_t>(gv)];
      if (result.unchanged[static_cast<size_t>(p)]) {
        sp = transfer.at_vertex(p, v);
        continue;
      }
      const Source& so = sources[static_cast<size_t>(p)][static_cast<size_t>(v)];
      switch (so.kind) {
        case Source::kOldVertex:
          sp = transfer.at_vertex(p, so.from);
          break;
        case Source::kEdge:
          sp = transfer.on_edge(p, so.from, so.to, so.t);
          break;
        case Source::kRestPoint:
          sp = transfer.at_rest_point(p, so.q);
          break;
      }
    }
  }
  result.state.garment = g.embedding;
  result.state.body = state.body;
  return result;
}

}  // namespace tightfit
