#include "tightfit/io/pattern_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "tightfit/io/pattern_validate.hpp"

namespace tightfit {
namespace {

constexpr double kMmPerM = 1000.0;
constexpr double kArcToleranceMm = 0.05;

/// Cumulative arc length along an open polyline.
std::vector<double> arc_lengths(const std::vector<Vec2>& line) {
  std::vector<double> s(line.size(), 0.0);
  for (size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

Vec2 rest_mm(const PatternPiece& piece, int v) {
  return piece.rest.row(v).transpose() * kMmPerM;
}

/// Loop edge index of the boundary edge between consecutive boundary vertices u → w,
/// and whether the loop runs u → w (true) or w → u (false).
struct LoopEdge {
  int edge;
  bool forward;
};

class BoundaryIndex {
 public:
  explicit BoundaryIndex(const PatternPiece& piece) : size_(static_cast<int>(piece.boundary.size())) {
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

std::string format_mm(double mm) {
  std::ostringstream out;
  out << std::round(mm * 10.0) / 10.0;
  return out.str();
}

void add_notches(const Pattern& pattern, const Seam& seam, const PatternExportOptions& options,
                 const std::vector<BoundaryIndex>& indices, std::vector<PieceDrawing>& drawings) {
  const SeamSide* sides[2] = {&seam.a, &seam.b};
  std::vector<Vec2> points[2];
  for (int s = 0; s < 2; ++s) {
    const PatternPiece& piece = pattern.pieces[static_cast<size_t>(sides[s]->piece)];
    for (int v : sides[s]->vertices) points[s].push_back(rest_mm(piece, v));
  }
  const SeamNotchParameters params =
      seam_notch_parameters(points[0], points[1], options.notch_spacing * kMmPerM);
  for (int s = 0; s < 2; ++s) {
    const int p = sides[s]->piece;
    PieceDrawing& drawing = drawings[static_cast<size_t>(p)];
    const auto& vertices = sides[s]->vertices;
    for (size_t k = 0; k < params.t.size(); ++k) {
      const auto i = static_cast<size_t>(params.segment[k]);
      const Vec2 a = points[s][i];
      const Vec2 b = points[s][i + 1];
      const LoopEdge edge = indices[static_cast<size_t>(p)].edge(vertices[i], vertices[i + 1]);
      Vec2 dir = (b - a).normalized();
      if (!edge.forward) dir = -dir;
      const Vec2 outward(dir.y(), -dir.x());
      const Vec2 sew = a + (b - a) * params.t[k];
      const double allowance = drawing.allowance[static_cast<size_t>(edge.edge)];
      drawing.notches.push_back({seam.name, s, static_cast<int>(k), sew, sew + outward * allowance});
    }
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
                       : "Seam allowance " + format_mm(options.seam_allowance * kMmPerM) +
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
  for (size_t p = 0; p < drawings.size(); ++p) {
    PieceDrawing& d = drawings[p];
    d.cut_line = offset_polygon(d.sew_line, d.allowance, options.corner_style, options.mitre_limit,
                                kArcToleranceMm);
    d.centroid = area_centroid(d.sew_line);
    add_grain(d, pattern.pieces[p].grain);
  }
  for (const Seam& seam : pattern.seams) add_notches(pattern, seam, options, indices, drawings);
  return drawings;
}

}  // namespace tightfit
