#include "tightfit/design/remesh_boundary.hpp"

#include <set>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/boundary_resampling.hpp"

namespace tightfit {
namespace {

std::string piece_source(const PatternPiece& piece) { return "pattern piece " + piece.name; }

BoundaryLoop boundary_loop(const PatternPiece& piece) {
  BoundaryLoop loop;
  loop.vertices = piece.boundary;
  loop.pos.assign(static_cast<size_t>(piece.rest.rows()), -1);
  for (int k = 0; k < loop.size(); ++k)
    loop.pos[static_cast<size_t>(loop.vertices[static_cast<size_t>(k)])] = k;
  return loop;
}

/// Loop positions of the break points of every piece: its corners, the ends of its seam
/// sides and of its open pinned boundaries (position 0 when it has none).
std::vector<std::set<int>> break_points(const Pattern& pattern, const BoundaryPlan& plan) {
  const size_t np = pattern.pieces.size();
  std::vector<std::set<int>> breaks(np);
  for (size_t p = 0; p < np; ++p) {
    const BoundaryLoop& loop = plan.loops[p];
    for (int c : pattern.pieces[p].corners)
      if (c >= 0 && c < static_cast<int>(loop.pos.size()) && loop.pos[static_cast<size_t>(c)] >= 0)
        breaks[p].insert(loop.pos[static_cast<size_t>(c)]);
  }
  for (const std::array<SideRun, 2>& sides : plan.sides)
    for (const SideRun& run : sides) {
      breaks[static_cast<size_t>(run.piece)].insert(run.loop_pos.front());
      breaks[static_cast<size_t>(run.piece)].insert(run.loop_pos.back());
    }
  for (const PinnedBoundary& pin : pattern.pinned) {
    const BoundaryLoop& loop = plan.loops[static_cast<size_t>(pin.piece)];
    if (static_cast<int>(pin.vertices.size()) == loop.size() || pin.vertices.empty() ||
        plan.on_hole(pin))
      continue;
    const SideRun run = side_run(loop, SeamSide{pin.piece, pin.vertices},
                                 pattern.pieces[static_cast<size_t>(pin.piece)],
                                 "pinned boundary \"" + pin.name + "\"");
    breaks[static_cast<size_t>(pin.piece)].insert(run.loop_pos.front());
    breaks[static_cast<size_t>(pin.piece)].insert(run.loop_pos.back());
  }
  for (std::set<int>& b : breaks)
    if (b.empty()) b.insert(0);
  return breaks;
}

}  // namespace

SideRun side_run(const BoundaryLoop& loop, const SeamSide& side, const PatternPiece& piece,
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

bool BoundaryPlan::on_hole(const PinnedBoundary& pin) const {
  const BoundaryLoop& loop = loops[static_cast<size_t>(pin.piece)];
  return !pin.vertices.empty() && loop.pos[static_cast<size_t>(pin.vertices.front())] < 0;
}

BoundaryPlan plan_boundary(const Pattern& pattern) {
  BoundaryPlan plan;
  for (const PatternPiece& piece : pattern.pieces) plan.loops.push_back(boundary_loop(piece));
  for (const Seam& seam : pattern.seams) {
    // Checked first: a side without vertices has no ends to cut at.
    if (seam.a.vertices.size() != seam.b.vertices.size() || seam.a.vertices.size() < 2)
      throw InputError("pattern",
                       "seam \"" + seam.name + "\" has sides of unequal or too few vertices");
    std::array<SideRun, 2> sides;
    int k = 0;
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      sides[static_cast<size_t>(k++)] =
          side_run(plan.loops[static_cast<size_t>(side->piece)], *side,
                   pattern.pieces[static_cast<size_t>(side->piece)], "seam \"" + seam.name + "\"");
    }
    plan.sides.push_back(std::move(sides));
  }
  const std::vector<std::set<int>> breaks = break_points(pattern, plan);

  // Seam split indices, unit starts per piece, and which loop edge a side covers.
  for (const BoundaryLoop& loop : plan.loops)
    plan.cover.emplace_back(static_cast<size_t>(loop.size()), EdgeCover{});
  std::vector<std::set<int>> unit_starts = breaks;
  for (size_t s = 0; s < plan.sides.size(); ++s) {
    std::set<int> split;
    for (int k = 0; k < 2; ++k) {
      const SideRun& run = plan.sides[s][static_cast<size_t>(k)];
      const int m = static_cast<int>(run.loop_pos.size()) - 1;
      for (int i = 0; i <= m; ++i)
        if (breaks[static_cast<size_t>(run.piece)].count(run.loop_pos[static_cast<size_t>(i)]))
          split.insert(i);
      for (int i = 0; i < m; ++i) {
        const int edge = run.dir > 0 ? run.loop_pos[static_cast<size_t>(i)]
                                     : run.loop_pos[static_cast<size_t>(i + 1)];
        EdgeCover& c = plan.cover[static_cast<size_t>(run.piece)][static_cast<size_t>(edge)];
        if (c.seam >= 0)
          throw InputError(piece_source(pattern.pieces[static_cast<size_t>(run.piece)]),
                           "a boundary edge is on two seam sides");
        c = {static_cast<int>(s), k};
      }
    }
    // Both ends of each side are break points: the split holds 0 and the last index.
    if (split.size() < 2)
      throw std::logic_error("plan_boundary: a seam side's ends are not break points");
    plan.splits.emplace_back(split.begin(), split.end());
    for (const SideRun& run : plan.sides[s])
      for (int i : plan.splits.back())
        unit_starts[static_cast<size_t>(run.piece)].insert(run.loop_pos[static_cast<size_t>(i)]);
  }
  for (const std::set<int>& u : unit_starts) plan.unit_starts.emplace_back(u.begin(), u.end());
  return plan;
}

std::vector<SeamResampling> resample_seams(const Garment& old_garment, const Points3& positions,
                                           const BoundaryPlan& plan,
                                           const std::vector<bool>& remesh,
                                           const std::vector<double>& edge_length) {
  const Pattern& pattern = old_garment.pattern;
  std::vector<SeamResampling> out(pattern.seams.size());
  for (size_t s = 0; s < pattern.seams.size(); ++s) {
    const Seam& seam = pattern.seams[s];
    const std::vector<int>& split = plan.splits[s];
    const int pa = seam.a.piece, pb = seam.b.piece;
    const bool resample = remesh[static_cast<size_t>(pa)] || remesh[static_cast<size_t>(pb)];
    std::vector<SeamSample>& samples = out[s].samples;
    for (size_t r = 0; r + 1 < split.size(); ++r) {
      const int i0 = split[r], i1 = split[r + 1];
      out[s].range_offset.push_back(static_cast<int>(samples.size()));
      if (!resample) {
        for (int i = i0; i < i1; ++i) samples.push_back({i, 0.0});
        continue;
      }
      const std::vector<int> a(seam.a.vertices.begin() + i0, seam.a.vertices.begin() + i1 + 1);
      const std::vector<int> b(seam.b.vertices.begin() + i0, seam.b.vertices.begin() + i1 + 1);
      std::vector<int> welded;  // side a's garment vertices
      for (int v : a)
        welded.push_back(old_garment.topology->pattern_to_garment[static_cast<size_t>(
            old_garment.topology->piece_offset[static_cast<size_t>(pa)] + v)]);
      const std::vector<double> cum = cumulative_lengths(positions, welded);
      const double la = cumulative_lengths(pattern.pieces[static_cast<size_t>(pa)].rest, a).back();
      const double lb = cumulative_lengths(pattern.pieces[static_cast<size_t>(pb)].rest, b).back();
      const double h =
          0.5 * (edge_length[static_cast<size_t>(pa)] + edge_length[static_cast<size_t>(pb)]);
      const int n = seam_edge_count(la, lb, h, min_edge_count(plan.num_units(pa)),
                                    min_edge_count(plan.num_units(pb)));
      samples.push_back({i0, 0.0});
      for (int k = 1; k < n; ++k) {
        const ArcPoint at = locate_arc(cum, cum.back() * k / n);
        samples.push_back({i0 + at.edge, at.t});
      }
    }
    out[s].range_offset.push_back(static_cast<int>(samples.size()));
    samples.push_back({split.back(), 0.0});
  }
  return out;
}

}  // namespace tightfit
