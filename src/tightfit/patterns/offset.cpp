#include "tightfit/patterns/offset.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"

namespace tightfit {
namespace {

/// Outward unit normal of a counter-clockwise edge direction.
Vec2 outward(const Vec2& direction) { return Vec2(direction.y(), -direction.x()); }

struct Edge {
  Vec2 start;
  Vec2 end;
  Vec2 dir;  ///< unit
  double distance;
};

/// Appends the arc around `corner` from normal `n0` (radius `r0`) turning
/// counter-clockwise by `angle` to normal `n1` (radius `r1`).
void append_arc(std::vector<Vec2>& out, const Vec2& corner, const Vec2& n0, double r0, double r1,
                double angle, double tolerance) {
  const double r = std::max(r0, r1);
  double step = std::numbers::pi / 2.0;
  if (r > tolerance) step = std::min(step, 2.0 * std::acos(1.0 - tolerance / r));
  const int segments = std::max(1, static_cast<int>(std::ceil(angle / step)));
  for (int k = 0; k <= segments; ++k) {
    const double f = static_cast<double>(k) / segments;
    const double phi = f * angle;
    const Vec2 n(std::cos(phi) * n0.x() - std::sin(phi) * n0.y(),
                 std::sin(phi) * n0.x() + std::cos(phi) * n0.y());
    out.push_back(corner + n * ((1.0 - f) * r0 + f * r1));
  }
}

/// The raw offset curve: offset edges joined at the corners; may overlap itself.
std::vector<Vec2> raw_offset(const std::vector<Edge>& edges, CornerStyle style, double mitre_limit,
                             double tolerance) {
  std::vector<Vec2> out;
  const size_t m = edges.size();
  for (size_t k = 0; k < m; ++k) {
    const Edge& e0 = edges[(k + m - 1) % m];
    const Edge& e1 = edges[k];
    const Vec2& p = e1.start;
    const Vec2 n0 = outward(e0.dir);
    const Vec2 n1 = outward(e1.dir);
    const double a0 = e0.distance;
    const double a1 = e1.distance;
    const double c = cross2(e0.dir, e1.dir);
    const double d = e0.dir.dot(e1.dir);
    const double angle = std::atan2(c, d);  // turn to the left, (-pi, pi]
    if (std::abs(angle) < 1e-9) {           // straight on
      out.push_back(p + n0 * a0);
      if (std::abs(a0 - a1) > 1e-12) out.push_back(p + n1 * a1);
    } else if (angle > 0.0 || d < -1.0 + 1e-12) {  // convex corner (or full reversal)
      const double turn = angle > 0.0 ? angle : std::numbers::pi;
      const double amax = std::max(a0, a1);
      bool mitred = false;
      if (style == CornerStyle::kMitre && std::abs(c) > 1e-12) {
        // p + n0 a0 + t d0 = p + n1 a1 + s d1  →  solve for t.
        const Vec2 rhs = n1 * a1 - n0 * a0;
        const double t = cross2(rhs, e1.dir) / c;
        const Vec2 mitre = p + n0 * a0 + e0.dir * t;
        if ((mitre - p).norm() <= mitre_limit * amax + 1e-12) {
          out.push_back(mitre);
          mitred = true;
        }
      }
      if (!mitred) {
        if (amax <= 0.0) {
          out.push_back(p);
        } else {
          append_arc(out, p, n0, a0, a1, turn, tolerance);
        }
      }
    } else {  // concave corner: pivot through the corner; the envelope removes the loop
      out.push_back(p + n0 * a0);
      out.push_back(p);
      out.push_back(p + n1 * a1);
    }
  }
  // Drop consecutive duplicates (zero allowance makes pivots coincide).
  std::vector<Vec2> clean;
  for (const Vec2& q : out) {
    if (clean.empty() || (q - clean.back()).norm() > 1e-12) clean.push_back(q);
  }
  while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= 1e-12) clean.pop_back();
  return clean;
}

struct UnionFind {
  std::vector<int> parent;
  int add() {
    parent.push_back(static_cast<int>(parent.size()));
    return parent.back();
  }
  int find(int x) {
    while (parent[static_cast<size_t>(x)] != x) {
      parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
      x = parent[static_cast<size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<size_t>(find(a))] = find(b); }
};

/// The outer envelope of a closed polyline: split it at its self-intersections and walk
/// around the outside, always taking the rightmost turn.
Polygon2 outer_envelope(const std::vector<Vec2>& curve, double scale) {
  const size_t m = curve.size();
  const double eps = 1e-12 * std::max(1.0, scale);
  std::vector<Vec2> positions(curve);
  UnionFind nodes;
  for (size_t i = 0; i < m; ++i) nodes.add();
  // Per segment: (parameter, node) splits; vertex nodes at t = 0 and t = 1.
  std::vector<std::vector<std::pair<double, int>>> splits(m);
  for (size_t i = 0; i < m; ++i) {
    splits[i].push_back({0.0, static_cast<int>(i)});
    splits[i].push_back({1.0, static_cast<int>((i + 1) % m)});
  }
  // Sweep over segments sorted by their smallest x.
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t{0});
  auto xmin = [&](size_t i) { return std::min(curve[i].x(), curve[(i + 1) % m].x()); };
  auto xmax = [&](size_t i) { return std::max(curve[i].x(), curve[(i + 1) % m].x()); };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return xmin(a) < xmin(b); });
  // The vertex node at a segment end, or -1 inside the segment.
  auto node_at = [&](size_t segment, double t) {
    if (t <= 1e-12) return static_cast<int>(segment);
    if (t >= 1.0 - 1e-12) return static_cast<int>((segment + 1) % m);
    return -1;
  };
  for (size_t oi = 0; oi < m; ++oi) {
    const size_t i = order[oi];
    const Vec2 p = curve[i];
    const Vec2 r = curve[(i + 1) % m] - p;
    const double iymin = std::min(p.y(), curve[(i + 1) % m].y());
    const double iymax = std::max(p.y(), curve[(i + 1) % m].y());
    for (size_t oj = oi + 1; oj < m && xmin(order[oj]) <= xmax(i) + eps; ++oj) {
      const size_t j = order[oj];
      if (j == (i + 1) % m || i == (j + 1) % m) continue;  // neighbours share a vertex
      const Vec2 q = curve[j];
      const Vec2 s = curve[(j + 1) % m] - q;
      if (std::max(q.y(), curve[(j + 1) % m].y()) < iymin - eps ||
          std::min(q.y(), curve[(j + 1) % m].y()) > iymax + eps) {
        continue;
      }
      const double denom = cross2(r, s);
      if (std::abs(denom) <= 1e-15 * r.norm() * s.norm()) continue;  // parallel
      const Vec2 qp = q - p;
      const double t = cross2(qp, s) / denom;
      const double u = cross2(qp, r) / denom;
      const double tol = 1e-12;
      if (t < -tol || t > 1.0 + tol || u < -tol || u > 1.0 + tol) continue;
      const double tc = std::clamp(t, 0.0, 1.0);
      const double uc = std::clamp(u, 0.0, 1.0);
      const Vec2 x = p + r * tc;
      int ni = node_at(i, tc);
      int nj = node_at(j, uc);
      if (ni < 0 && nj < 0) {
        ni = nodes.add();
        positions.push_back(x);
        nj = ni;
      } else if (ni < 0) {
        ni = nj;
      } else if (nj < 0) {
        nj = ni;
      } else {
        nodes.unite(ni, nj);
      }
      splits[i].push_back({tc, ni});
      splits[j].push_back({uc, nj});
    }
  }
  // Directed graph edges between consecutive split nodes of each segment.
  std::vector<std::vector<int>> outgoing(positions.size());
  for (size_t i = 0; i < m; ++i) {
    auto& list = splits[i];
    std::sort(list.begin(), list.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t k = 0; k + 1 < list.size(); ++k) {
      const int from = nodes.find(list[k].second);
      const int to = nodes.find(list[k + 1].second);
      if (from == to) continue;
      auto& out = outgoing[static_cast<size_t>(from)];
      if (std::find(out.begin(), out.end(), to) == out.end()) out.push_back(to);
    }
  }
  // Start at the lowest-left node: it is on the outer boundary.
  int start = -1;
  for (size_t v = 0; v < positions.size(); ++v) {
    if (nodes.find(static_cast<int>(v)) != static_cast<int>(v) || outgoing[v].empty()) continue;
    if (start < 0) {
      start = static_cast<int>(v);
      continue;
    }
    const Vec2& a = positions[v];
    const Vec2& b = positions[static_cast<size_t>(start)];
    if (a.x() < b.x() || (a.x() == b.x() && a.y() < b.y())) start = static_cast<int>(v);
  }
  if (start < 0) throw SolverError("seam allowance offset: empty outline");
  auto pos = [&](int v) { return positions[static_cast<size_t>(v)]; };
  int current = start;
  int next = -1;
  double best = 0.0;
  for (int w : outgoing[static_cast<size_t>(start)]) {
    const Vec2 d = pos(w) - pos(start);
    const double angle = std::atan2(d.y(), d.x());
    if (next < 0 || angle < best) {
      next = w;
      best = angle;
    }
  }
  Polygon2 result{pos(start)};
  size_t edge_count = 0;
  for (const auto& out : outgoing) edge_count += out.size();
  for (size_t steps = 0; next != start; ++steps) {
    if (steps > edge_count) throw SolverError("seam allowance offset: cannot trace the cut line");
    result.push_back(pos(next));
    const Vec2 din = pos(next) - pos(current);
    int chosen = -1;
    double chosen_turn = 0.0;
    for (int w : outgoing[static_cast<size_t>(next)]) {
      const Vec2 dout = pos(w) - pos(next);
      double turn = std::atan2(cross2(din, dout), din.dot(dout));
      if (turn <= -std::numbers::pi + 1e-12) turn = std::numbers::pi;  // reversal last
      if (chosen < 0 || turn < chosen_turn) {
        chosen = w;
        chosen_turn = turn;
      }
    }
    if (chosen < 0) throw SolverError("seam allowance offset: open cut line");
    current = next;
    next = chosen;
  }
  return result;
}

}  // namespace

Vec2 area_centroid(const Polygon2& polygon) {
  // Relative to the first point for accuracy.
  const Vec2 origin = polygon.empty() ? Vec2::Zero() : polygon.front();
  double area2 = 0.0;
  Vec2 sum = Vec2::Zero();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 a = polygon[i] - origin;
    const Vec2 b = polygon[(i + 1) % polygon.size()] - origin;
    const double w = cross2(a, b);
    area2 += w;
    sum += (a + b) * w;
  }
  return origin + sum / (3.0 * area2);
}

Polygon2 offset_polygon(const Polygon2& polygon, const std::vector<double>& distance,
                        CornerStyle style, double mitre_limit, double arc_tolerance) {
  if (distance.size() != polygon.size()) {
    throw std::invalid_argument("offset_polygon: one distance per edge is required");
  }
  std::vector<Edge> edges;
  double scale = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    const double length = (b - a).norm();
    scale = std::max({scale, std::abs(a.x()), std::abs(a.y()), distance[i]});
    if (length <= 1e-12) continue;  // repeated point
    edges.push_back({a, b, (b - a) / length, distance[i]});
  }
  if (edges.size() < 3) throw SolverError("seam allowance offset: degenerate outline");
  const std::vector<Vec2> raw = raw_offset(edges, style, mitre_limit, arc_tolerance);
  return outer_envelope(raw, scale);
}

}  // namespace tightfit
