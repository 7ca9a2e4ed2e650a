#include "tightfit/patterns/labels.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tightfit/common/planar.hpp"

namespace tightfit {
namespace {

constexpr double kDescent = 0.25;
constexpr double kLinePitch = 1.4;
/// |direction.y| above which a text counts as vertical (within about 11°).
constexpr double kNearlyVertical = 0.98;

bool inside(const Polygon2& polygon, const Vec2& q) {
  return inside_polygon(
      polygon.size(), [&](size_t i) { return polygon[i]; }, q);
}

bool segments_cross(const Vec2& p, const Vec2& p2, const Vec2& q, const Vec2& q2) {
  const Vec2 r = p2 - p;
  const Vec2 s = q2 - q;
  const double denom = cross2(r, s);
  if (std::abs(denom) < 1e-14) return false;
  const double t = cross2(q - p, s) / denom;
  const double u = cross2(q - p, r) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

double outline_distance(const Polygon2& polygon, const Vec2& q) {
  double best = 1e300;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    const Vec2 d = b - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (q - (a + d * t)).norm());
  }
  return best;
}

/// The block's lines at `scale` with the block's top-left corner at `corner`.
std::vector<PlacedText> block_at(const std::vector<TextLine>& lines, double scale,
                                 const Vec2& corner) {
  std::vector<PlacedText> out;
  double y = 0.0;
  for (const TextLine& line : lines) {
    const double h = line.height * scale;
    out.push_back({line.text, corner + Vec2(0.0, y - h), Vec2::UnitX(), h, line.bold});
    y -= kLinePitch * h;
  }
  return out;
}

Vec2 block_size(const std::vector<TextLine>& lines, double scale) {
  double w = 0.0;
  double h = 0.0;
  for (const TextLine& line : lines) {
    w = std::max(w, text_length(line.text, line.height * scale));
    h += kLinePitch * line.height * scale;
  }
  return {w, h};
}

bool block_inside(const std::vector<PlacedText>& block, const Polygon2& polygon,
                  const std::vector<Polygon2>& holes) {
  return std::all_of(block.begin(), block.end(), [&](const PlacedText& t) {
    return text_inside(t, polygon) &&
           std::all_of(holes.begin(), holes.end(),
                       [&](const Polygon2& hole) { return text_clear_of(t, hole); });
  });
}

}  // namespace

double text_length(const std::string& text, double height) {
  size_t code_points = 0;
  for (char c : text) code_points += (static_cast<unsigned char>(c) & 0xc0u) != 0x80u ? 1 : 0;
  return kTextAdvance * height * static_cast<double>(code_points);
}

std::array<Vec2, 4> text_box(const PlacedText& text) {
  const Vec2 d = text.direction;
  const Vec2 up(-d.y(), d.x());
  const Vec2 a = text.at - up * (kDescent * text.height);
  const Vec2 along = d * text_length(text.text, text.height);
  const Vec2 tall = up * ((1.0 + kDescent) * text.height);
  return {a, a + along, a + along + tall, a + tall};
}

bool text_inside(const PlacedText& text, const Polygon2& polygon) {
  const std::array<Vec2, 4> box = text_box(text);
  for (size_t k = 0; k < 4; ++k) {
    const Vec2& a = box[k];
    const Vec2& b = box[(k + 1) % 4];
    if (!inside(polygon, a) || !inside(polygon, 0.5 * (a + b))) return false;
    for (size_t i = 0; i < polygon.size(); ++i)
      if (segments_cross(a, b, polygon[i], polygon[(i + 1) % polygon.size()])) return false;
  }
  return true;
}

bool text_clear_of(const PlacedText& text, const Polygon2& hole) {
  const std::array<Vec2, 4> box = text_box(text);
  for (size_t k = 0; k < 4; ++k) {
    const Vec2& a = box[k];
    const Vec2& b = box[(k + 1) % 4];
    if (inside(hole, a) || inside(hole, 0.5 * (a + b))) return false;
    for (size_t i = 0; i < hole.size(); ++i)
      if (segments_cross(a, b, hole[i], hole[(i + 1) % hole.size()])) return false;
  }
  // A hole entirely inside the box.
  return hole.empty() || !inside_polygon(
                             4, [&](size_t i) { return box[i]; }, hole.front());
}

std::vector<PlacedText> place_text_block(const Polygon2& polygon,
                                         const std::vector<TextLine>& lines, const Vec2& preferred,
                                         const std::vector<Polygon2>& holes) {
  if (lines.empty()) return {};
  double smallest = 1e300;
  for (const TextLine& line : lines) smallest = std::min(smallest, line.height);
  const double min_scale = std::min(1.0, kMinTextHeightMm / smallest);
  std::vector<double> scales;
  for (double s = 1.0; s > min_scale + 1e-9; s -= 0.1) scales.push_back(s);
  scales.push_back(min_scale);

  // Spots (block centres), best first: right of the preferred point (clear of a grain
  // line through it), centred on it, then interior grid points farthest from the outline.
  Vec2 lo = polygon.front();
  Vec2 hi = polygon.front();
  for (const Vec2& q : polygon) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  std::vector<std::pair<double, Vec2>> grid;
  constexpr int kGrid = 16;
  for (int i = 0; i <= kGrid; ++i) {
    for (int j = 0; j <= kGrid; ++j) {
      const Vec2 q = lo + Vec2((hi - lo).x() * i / kGrid, (hi - lo).y() * j / kGrid);
      if (!inside(polygon, q)) continue;
      double clearance = outline_distance(polygon, q);
      bool in_hole = false;
      for (const Polygon2& hole : holes) {
        in_hole = in_hole || inside(hole, q);
        clearance = std::min(clearance, outline_distance(hole, q));
      }
      if (!in_hole) grid.emplace_back(clearance, q);
    }
  }
  std::stable_sort(grid.begin(), grid.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (double scale : scales) {
    const Vec2 size = block_size(lines, scale);
    std::vector<Vec2> corners = {preferred + Vec2(3.0, 0.5 * size.y()),
                                 preferred + Vec2(-0.5 * size.x(), 0.5 * size.y())};
    for (const auto& g : grid) corners.push_back(g.second + Vec2(-0.5 * size.x(), 0.5 * size.y()));
    for (const Vec2& corner : corners) {
      std::vector<PlacedText> block = block_at(lines, scale, corner);
      if (block_inside(block, polygon, holes)) return block;
    }
  }
  const Vec2 size = block_size(lines, min_scale);
  const Vec2 centre = grid.empty() ? preferred : grid.front().second;
  return block_at(lines, min_scale, centre + Vec2(-0.5 * size.x(), 0.5 * size.y()));
}

PlacedText place_along_side(const Polygon2& polygon, const std::vector<Vec2>& side,
                            const std::string& text, double height, double gap,
                            double from_end_mm) {
  std::vector<double> s(side.size(), 0.0);
  for (size_t i = 1; i < side.size(); ++i) s[i] = s[i - 1] + (side[i] - side[i - 1]).norm();
  const double length = s.back();
  // Point and unit tangent at arc length t.
  auto at_arc = [&](double t, Vec2& tangent) {
    size_t k = 0;
    while (k + 2 < side.size() && s[k + 1] < t) ++k;
    const Vec2 a = side[k];
    const Vec2 b = side[k + 1];
    const double span = s[k + 1] - s[k];
    tangent = span > 0.0 ? Vec2((b - a) / span) : Vec2(Vec2::UnitX());
    return span > 0.0 ? Vec2(a + (b - a) * ((t - s[k]) / span)) : a;
  };
  PlacedText placed{text, side.front(), Vec2::UnitX(), height, false};
  for (double h = height;; h = std::max(kMinTextHeightMm, 0.85 * h)) {
    const double along = text_length(text, h);
    double centre = 0.5 * length;
    if (from_end_mm >= 0.0) centre = std::max(0.5 * length, length - from_end_mm - 0.5 * along);
    Vec2 d;
    const Vec2 mid = at_arc(centre, d);
    // Left to right; (nearly) vertical text reads bottom to top.
    if (std::abs(d.y()) > kNearlyVertical ? d.y() < 0.0 : d.x() < 0.0) d = -d;
    const Vec2 up(-d.y(), d.x());
    // The inward normal: the side of the outline the polygon's interior is on.
    const Vec2 inward = inside(polygon, mid + up * 0.5) ? up : Vec2(-up);
    const double offset = inward.dot(up) > 0.0 ? gap + kDescent * h : gap + h;
    placed = {text, mid + inward * offset - d * (0.5 * along), d, h, false};
    if (text_inside(placed, polygon) || h <= kMinTextHeightMm) break;
  }
  return placed;
}

}  // namespace tightfit
