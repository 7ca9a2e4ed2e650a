#include "tightfit/patterns/drawing.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "tightfit/patterns/piece_texts.hpp"
#include "tightfit/patterns/truing.hpp"
#include "tightfit/patterns/validate.hpp"

namespace tightfit {
namespace {

constexpr double kArcToleranceMm = 0.05;
/// Turning angle (rad) above which a boundary vertex is a corner even when the pattern
/// does not list it.
constexpr double kSharpTurn = 0.5235987755982988;  // 30°
/// Largest spacing (mm) of the points sampled on a trued curve.
constexpr double kTruedSpacingMm = 2.0;

/// Cumulative arc length along an open polyline.
std::vector<double> arc_lengths(const std::vector<Vec2>& line) {
  std::vector<double> s(line.size(), 0.0);
  for (size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

/// Loop edge index of the boundary edge between consecutive boundary vertices u → w,
/// and whether the loop runs u → w (true) or w → u (false).
struct LoopEdge {
  int edge;
  bool forward;
};

class BoundaryIndex {
 public:
  explicit BoundaryIndex(const PatternPiece& piece)
      : size_(static_cast<int>(piece.boundary.size())) {
    for (int k = 0; k < size_; ++k) position_[piece.boundary[static_cast<size_t>(k)]] = k;
  }
  LoopEdge edge(int u, int w) const {
    const int pu = position_.at(u);
    const int pw = position_.at(w);
    if ((pu + 1) % size_ == pw) return {pu, true};
    return {pw, false};
  }

 private:
  int size_;
  std::unordered_map<int, int> position_;
};

/// Sets the allowance of every loop edge of a boundary polyline.
void apply_allowance(std::vector<double>& allowance, const BoundaryIndex& index,
                     const std::vector<int>& vertices, double value_mm) {
  for (size_t i = 0; i + 1 < vertices.size(); ++i) {
    allowance[static_cast<size_t>(index.edge(vertices[i], vertices[i + 1]).edge)] = value_mm;
  }
}

/// A notch before truing: where it sits on the piece's boundary loop.
struct PendingNotch {
  Notch notch;
  int edge = 0;    ///< loop edge (loop point edge → edge+1)
  double t = 0.0;  ///< parameter along the loop edge, 0 … 1
  Vec2 direction;  ///< unit direction of the loop edge (counter-clockwise)
  /// At the seam's ends: the unit direction along the edge into the seam (a double
  /// notch starts at the end and runs inward so that both ticks stay on the seam);
  /// zero elsewhere (the ticks are centred on the notch).
  Vec2 into_seam = Vec2::Zero();
};

void add_notches(const Pattern& pattern, const Seam& seam, const PatternExportOptions& options,
                 const std::vector<BoundaryIndex>& indices,
                 std::vector<std::vector<PendingNotch>>& pending) {
  const SeamSide* sides[2] = {&seam.a, &seam.b};
  std::vector<Vec2> points[2];
  for (int s = 0; s < 2; ++s) {
    const PatternPiece& piece = pattern.pieces[static_cast<size_t>(sides[s]->piece)];
    for (int v : sides[s]->vertices) points[s].push_back(rest_mm(piece, v));
  }
  const SeamNotchParameters params =
      seam_notch_parameters(points[0], points[1], options.notch_spacing * kMmPerM);
  const auto style_it = options.seam_notch_styles.find(seam.name);
  const NotchStyle style =
      style_it == options.seam_notch_styles.end() ? NotchStyle::kSingle : style_it->second;
  for (int s = 0; s < 2; ++s) {
    const int p = sides[s]->piece;
    const auto& vertices = sides[s]->vertices;
    for (size_t k = 0; k < params.t.size(); ++k) {
      const auto i = static_cast<size_t>(params.segment[k]);
      const LoopEdge edge = indices[static_cast<size_t>(p)].edge(vertices[i], vertices[i + 1]);
      // In loop order, so that the point equals the one inserted into the outline.
      const Vec2 a = edge.forward ? points[s][i] : points[s][i + 1];
      const Vec2 b = edge.forward ? points[s][i + 1] : points[s][i];
      double t = edge.forward ? params.t[k] : 1.0 - params.t[k];
      if (t < 1e-9) t = 0.0;
      if (t > 1.0 - 1e-9) t = 1.0;
      const Vec2 sew = t == 0.0 ? a : t == 1.0 ? b : Vec2(a + (b - a) * t);
      PendingNotch n;
      n.notch.seam = seam.name;
      n.notch.side = s;
      n.notch.index = static_cast<int>(k);
      n.notch.sew = sew;
      n.notch.style = style;
      n.edge = edge.edge;
      n.t = t;
      n.direction = (b - a).normalized();
      const Vec2 along_side = edge.forward ? n.direction : Vec2(-n.direction);
      if (k == 0) n.into_seam = along_side;
      if (k + 1 == params.t.size()) n.into_seam = -along_side;
      pending[static_cast<size_t>(p)].push_back(std::move(n));
    }
  }
}

/// The notch's ticks, `depth` mm long, outward from the sew line.
void cut_notch(PendingNotch& pending, double depth, const PatternExportOptions& options) {
  Notch& n = pending.notch;
  const Vec2 dir = pending.direction;
  const Vec2 outward(dir.y(), -dir.x());
  n.cut = n.sew + outward * depth;
  if (n.style == NotchStyle::kSingle) {
    n.ticks.push_back({n.sew, n.cut});
    return;
  }
  const double gap = options.double_notch_gap * kMmPerM;
  const std::array<Vec2, 2> starts =
      pending.into_seam.isZero()
          ? std::array<Vec2, 2>{n.sew - dir * (0.5 * gap), n.sew + dir * (0.5 * gap)}
          : std::array<Vec2, 2>{n.sew, n.sew + pending.into_seam * gap};
  for (const Vec2& start : starts) n.ticks.push_back({start, start + outward * depth});
}

/// Trues the sew line of piece `p` through its kept points (corners, sharp turns, ends
/// of seams and pinned boundaries, notch positions), offsets it by the allowances into
/// the cut line and cuts the notches.
void true_piece(const Pattern& pattern, size_t p, const PatternExportOptions& options,
                std::vector<PendingNotch>& notches, PieceDrawing& d) {
  const PatternPiece& piece = pattern.pieces[p];
  const size_t n = d.sew_line.size();
  std::unordered_map<int, size_t> position;
  for (size_t k = 0; k < n; ++k) position[piece.boundary[k]] = k;
  std::vector<bool> corner(n, false);
  std::vector<bool> end(n, false);
  for (int c : piece.corners)
    if (const auto it = position.find(c); it != position.end()) corner[it->second] = true;
  for (size_t k = 0; k < n; ++k)
    if (turning_angle(d.sew_line, k) > kSharpTurn) corner[k] = true;
  auto mark_ends = [&](int piece_index, const std::vector<int>& vertices) {
    if (static_cast<size_t>(piece_index) != p) return;
    for (int v : {vertices.front(), vertices.back()})
      if (const auto it = position.find(v); it != position.end()) end[it->second] = true;
  };
  for (const Seam& seam : pattern.seams) {
    mark_ends(seam.a.piece, seam.a.vertices);
    mark_ends(seam.b.piece, seam.b.vertices);
  }
  for (const PinnedBoundary& pin : pattern.pinned) mark_ends(pin.piece, pin.vertices);

  // The outline with the notch positions inserted (kept points).
  std::vector<std::vector<const PendingNotch*>> on_edge(n);
  std::vector<bool> vertex_notch(n, false);
  for (const PendingNotch& pn : notches) {
    const auto e = static_cast<size_t>(pn.edge);
    if (pn.t == 0.0) {
      vertex_notch[e] = true;
    } else if (pn.t == 1.0) {
      vertex_notch[(e + 1) % n] = true;
    } else {
      on_edge[e].push_back(&pn);
    }
  }
  Polygon2 outline;
  std::vector<int> outline_edge;
  std::vector<bool> keep;
  std::vector<bool> sharp;
  for (size_t k = 0; k < n; ++k) {
    outline.push_back(d.sew_line[k]);
    outline_edge.push_back(static_cast<int>(k));
    keep.push_back(corner[k] || end[k] || vertex_notch[k]);
    sharp.push_back(corner[k]);
    std::sort(on_edge[k].begin(), on_edge[k].end(),
              [](const PendingNotch* a, const PendingNotch* b) { return a->t < b->t; });
    for (const PendingNotch* pn : on_edge[k]) {
      if (pn->notch.sew == outline.back()) continue;
      outline.push_back(pn->notch.sew);
      outline_edge.push_back(static_cast<int>(k));
      keep.push_back(true);
      sharp.push_back(false);
    }
  }
  const TruedOutline trued =
      true_outline(outline, keep, sharp, options.true_tolerance * kMmPerM, kTruedSpacingMm);
  d.trued_sew_line = trued.points;
  std::vector<double> allowance;
  for (size_t k = 0; k < trued.points.size(); ++k) {
    const auto edge = static_cast<size_t>(outline_edge[static_cast<size_t>(trued.edge_source[k])]);
    allowance.push_back(d.allowance[edge]);
  }
  d.cut_line = offset_polygon(d.trued_sew_line, allowance, options.corner_style,
                              options.mitre_limit, kArcToleranceMm);
  for (PendingNotch& pn : notches) {
    const double depth =
        std::min(options.notch_depth * kMmPerM, d.allowance[static_cast<size_t>(pn.edge)]);
    cut_notch(pn, depth, options);
    d.notches.push_back(pn.notch);
  }
}

void add_grain(PieceDrawing& drawing, const Vec2& grain) {
  const Vec2 g = grain.normalized();
  double tmin = 0.0;
  double tmax = 0.0;
  for (const Vec2& q : drawing.sew_line) {
    const double t = (q - drawing.centroid).dot(g);
    tmin = std::min(tmin, t);
    tmax = std::max(tmax, t);
  }
  const double half = 0.6 * std::min(tmax, -tmin);
  drawing.grain_start = drawing.centroid - g * half;
  drawing.grain_end = drawing.centroid + g * half;
}

}  // namespace

SeamNotchParameters seam_notch_parameters(const std::vector<Vec2>& side_a,
                                          const std::vector<Vec2>& side_b, double spacing) {
  const std::vector<double> sa = arc_lengths(side_a);
  const std::vector<double> sb = arc_lengths(side_b);
  const double la = sa.back();
  const double lb = sb.back();
  const size_t n = side_a.size();
  std::vector<double> g(n);
  for (size_t i = 0; i < n; ++i) {
    const double fa = la > 0.0 ? sa[i] / la : static_cast<double>(i) / static_cast<double>(n - 1);
    const double fb = lb > 0.0 ? sb[i] / lb : static_cast<double>(i) / static_cast<double>(n - 1);
    g[i] = 0.5 * (fa + fb);
  }
  g.back() = 1.0;
  int intervals = 1;
  if (spacing > 0.0) {
    intervals = std::max(1, static_cast<int>(std::lround(0.5 * (la + lb) / spacing)));
  }
  SeamNotchParameters out;
  size_t segment = 0;
  for (int k = 0; k <= intervals; ++k) {
    const double f = static_cast<double>(k) / intervals;
    while (segment + 2 < n && g[segment + 1] < f) ++segment;
    const double span = g[segment + 1] - g[segment];
    const double t = span > 0.0 ? std::clamp((f - g[segment]) / span, 0.0, 1.0) : 0.0;
    out.segment.push_back(static_cast<int>(segment));
    out.t.push_back(t);
  }
  return out;
}

std::vector<PieceDrawing> draw_pattern_pieces(const Pattern& pattern,
                                              const PatternExportOptions& options,
                                              const std::string& source) {
  validate_pattern(pattern, source);
  validate_export_options(pattern, options, source);
  std::vector<PieceDrawing> drawings(pattern.pieces.size());
  std::vector<BoundaryIndex> indices;
  for (size_t p = 0; p < pattern.pieces.size(); ++p) {
    const PatternPiece& piece = pattern.pieces[p];
    PieceDrawing& d = drawings[p];
    d.name = piece.name;
    const auto quantity = options.quantities.find(piece.name);
    d.quantity = quantity == options.quantities.end() ? 1 : quantity->second;
    const auto annotation = options.annotations.find(piece.name);
    d.annotation = annotation != options.annotations.end()
                       ? annotation->second
                       : "Seam allowance " + label_number(options.seam_allowance * kMmPerM, 1) +
                             " mm included";
    for (int v : piece.boundary) d.sew_line.push_back(rest_mm(piece, v));
    for (const std::vector<int>& hole : piece.holes) {
      d.holes.emplace_back();
      for (int v : hole) d.holes.back().push_back(rest_mm(piece, v));
    }
    d.allowance.assign(piece.boundary.size(), options.seam_allowance * kMmPerM);
    indices.emplace_back(piece);
  }
  auto allowance_of = [&](const std::string& name) {
    const auto it = options.seam_allowances.find(name);
    return (it == options.seam_allowances.end() ? options.seam_allowance : it->second) * kMmPerM;
  };
  for (const PinnedBoundary& pin : pattern.pinned) {
    apply_allowance(drawings[static_cast<size_t>(pin.piece)].allowance,
                    indices[static_cast<size_t>(pin.piece)], pin.vertices, allowance_of(pin.name));
  }
  for (const Seam& seam : pattern.seams) {
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      apply_allowance(drawings[static_cast<size_t>(side->piece)].allowance,
                      indices[static_cast<size_t>(side->piece)], side->vertices,
                      allowance_of(seam.name));
    }
  }
  std::vector<std::vector<PendingNotch>> pending(drawings.size());
  for (const Seam& seam : pattern.seams) add_notches(pattern, seam, options, indices, pending);
  for (size_t p = 0; p < drawings.size(); ++p) {
    PieceDrawing& d = drawings[p];
    true_piece(pattern, p, options, pending[p], d);
    d.centroid = area_centroid(d.sew_line);
    add_grain(d, pattern.pieces[p].grain);
  }
  if (options.seam_labels) add_seam_texts(pattern, options, drawings);
  for (PieceDrawing& d : drawings) {
    d.label_lines = piece_label_lines(d, options);
    d.label = place_text_block(d.trued_sew_line, d.label_lines, d.centroid, d.holes);
  }
  return drawings;
}

}  // namespace tightfit
