#include "tightfit/patterns/truing.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "tightfit/common/planar.hpp"

namespace tightfit {
namespace {

double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (q - (a + d * t)).norm();
}

/// Distance from q to the open polyline `line`.
double polyline_distance(const Vec2& q, const std::vector<Vec2>& line) {
  if (line.size() == 1) return (q - line[0]).norm();
  double best = 1e300;
  for (size_t i = 0; i + 1 < line.size(); ++i)
    best = std::min(best, segment_distance(q, line[i], line[i + 1]));
  return best;
}

/// Point at parameter u ∈ [0, 1] of the centripetal Catmull-Rom segment p1 → p2
/// (Barry–Goldman pyramid, knots spaced by the square root of the chord lengths).
Vec2 catmull_rom(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double u) {
  auto knot = [](const Vec2& a, const Vec2& b) {
    return std::max(std::sqrt((b - a).norm()), 1e-12);
  };
  const double t0 = 0.0;
  const double t1 = t0 + knot(p0, p1);
  const double t2 = t1 + knot(p1, p2);
  const double t3 = t2 + knot(p2, p3);
  const double t = t1 + u * (t2 - t1);
  const Vec2 a1 = (t1 - t) / (t1 - t0) * p0 + (t - t0) / (t1 - t0) * p1;
  const Vec2 a2 = (t2 - t) / (t2 - t1) * p1 + (t - t1) / (t2 - t1) * p2;
  const Vec2 a3 = (t3 - t) / (t3 - t2) * p2 + (t - t2) / (t3 - t2) * p3;
  const Vec2 b1 = (t2 - t) / (t2 - t0) * a1 + (t - t0) / (t2 - t0) * a2;
  const Vec2 b2 = (t3 - t) / (t3 - t1) * a2 + (t - t1) / (t3 - t1) * a3;
  return (t2 - t) / (t2 - t1) * b1 + (t - t1) / (t2 - t1) * b2;
}

/// One stretch between kept points: input indices idx[0] … idx.back() in order.
class Stretch {
 public:
  /// `start_tangent` / `end_tangent`: the unit tangent the curve must have at its ends,
  /// or zero at a corner (the curve starts towards its next point there).
  Stretch(const Polygon2& polygon, std::vector<int> idx, const Vec2& start_tangent,
          const Vec2& end_tangent, double tolerance, double spacing)
      : polygon_(polygon),
        idx_(std::move(idx)),
        start_tangent_(start_tangent),
        end_tangent_(end_tangent),
        tolerance_(tolerance),
        spacing_(spacing) {}

  /// Reduces and refines; appends the stretch's points without its last one.
  void emit(TruedOutline& out) {
    std::vector<size_t> reduced = {0, idx_.size() - 1};
    std::vector<bool> linear(1, false);
    for (int guard = 0; guard < 100000; ++guard) {
      size_t worst = 0;
      double worst_error = 0.0;
      for (size_t s = 0; s + 1 < reduced.size(); ++s) {
        if (linear[s]) continue;
        const double e = error(reduced, s);
        if (e > worst_error) {
          worst_error = e;
          worst = s;
        }
      }
      if (worst_error <= tolerance_) break;
      const size_t a = reduced[worst];
      const size_t b = reduced[worst + 1];
      if (b == a + 1) {
        linear[worst] = true;
        continue;
      }
      // Insert the interior point farthest from the current curve segment.
      const std::vector<Vec2> curve = sample(reduced, worst);
      size_t pick = (a + b) / 2;
      double far = -1.0;
      for (size_t k = a + 1; k < b; ++k) {
        const double d = polyline_distance(point(k), curve);
        if (d > far) {
          far = d;
          pick = k;
        }
      }
      reduced.insert(reduced.begin() + static_cast<std::ptrdiff_t>(worst) + 1, pick);
      linear.insert(linear.begin() + static_cast<std::ptrdiff_t>(worst) + 1, false);
    }
    for (size_t s = 0; s + 1 < reduced.size(); ++s) {
      const int edge = idx_[reduced[s]];
      out.points.push_back(point(reduced[s]));
      out.source.push_back(idx_[reduced[s]]);
      out.edge_source.push_back(edge);
      if (linear[s]) {
        // Keep the polyline itself between these two (adjacent) points.
        continue;
      }
      const std::vector<Vec2> curve = sample(reduced, s);
      for (size_t k = 1; k + 1 < curve.size(); ++k) {
        out.points.push_back(curve[k]);
        out.source.push_back(-1);
        out.edge_source.push_back(edge);
      }
    }
  }

 private:
  Vec2 point(size_t k) const { return polygon_[static_cast<size_t>(idx_[k])]; }

  /// Control point r-1 … r+2 around reduced segment s, with phantom ends: at a corner
  /// the reflection of the next point (a natural end), elsewhere a point that gives the
  /// curve the prescribed tangent there (the Catmull-Rom tangent at p1 follows p2 − p0),
  /// so that the stretches on both sides of a smooth kept point meet without a kink.
  Vec2 control(const std::vector<size_t>& reduced, std::ptrdiff_t r) const {
    const auto m = static_cast<std::ptrdiff_t>(reduced.size());
    if (r < 0) {
      const Vec2 a = point(reduced[0]);
      const Vec2 next = point(reduced[1]);
      if (start_tangent_.isZero()) return 2.0 * a - next;
      return next - start_tangent_ * (2.0 * (next - a).norm());
    }
    if (r >= m) {
      const Vec2 b = point(reduced[static_cast<size_t>(m - 1)]);
      const Vec2 previous = point(reduced[static_cast<size_t>(m - 2)]);
      if (end_tangent_.isZero()) return 2.0 * b - previous;
      return previous + end_tangent_ * (2.0 * (b - previous).norm());
    }
    return point(reduced[static_cast<size_t>(r)]);
  }

  /// Samples of reduced segment s, both ends included (exactly the input points).
  std::vector<Vec2> sample(const std::vector<size_t>& reduced, size_t s) const {
    const auto r = static_cast<std::ptrdiff_t>(s);
    const Vec2 p0 = control(reduced, r - 1);
    const Vec2 p1 = control(reduced, r);
    const Vec2 p2 = control(reduced, r + 1);
    const Vec2 p3 = control(reduced, r + 2);
    const double chord = (p2 - p1).norm();
    const Vec2 mid = catmull_rom(p0, p1, p2, p3, 0.5);
    const Vec2 quarter = catmull_rom(p0, p1, p2, p3, 0.25);
    const double bend = std::max(segment_distance(mid, p1, p2), segment_distance(quarter, p1, p2));
    std::vector<Vec2> out = {p1};
    if (bend > 1e-9 * std::max(1.0, chord)) {
      const int count = std::clamp(static_cast<int>(std::ceil(chord / spacing_)), 2, 1000);
      for (int k = 1; k < count; ++k)
        out.push_back(catmull_rom(p0, p1, p2, p3, static_cast<double>(k) / count));
    }
    out.push_back(p2);
    return out;
  }

  /// Largest distance between reduced segment s's curve and its part of the polyline.
  double error(const std::vector<size_t>& reduced, size_t s) const {
    const std::vector<Vec2> curve = sample(reduced, s);
    std::vector<Vec2> line;
    for (size_t k = reduced[s]; k <= reduced[s + 1]; ++k) line.push_back(point(k));
    double e = 0.0;
    for (const Vec2& q : curve) e = std::max(e, polyline_distance(q, line));
    for (const Vec2& q : line) e = std::max(e, polyline_distance(q, curve));
    return e;
  }

  const Polygon2& polygon_;
  std::vector<int> idx_;
  Vec2 start_tangent_;
  Vec2 end_tangent_;
  double tolerance_;
  double spacing_;
};

/// Unit tangent of the closed polygon at point i: the direction between the points
/// `reach` (arc length) before and after it.
Vec2 smooth_tangent(const Polygon2& polygon, size_t i, double reach) {
  const size_t n = polygon.size();
  auto walk = [&](int step) {
    size_t k = i;
    double travelled = 0.0;
    for (size_t count = 0; count < n / 2; ++count) {
      const size_t next = step > 0 ? (k + 1) % n : (k + n - 1) % n;
      travelled += (polygon[next] - polygon[k]).norm();
      k = next;
      if (travelled >= reach) break;
    }
    return polygon[k];
  };
  const Vec2 d = walk(1) - walk(-1);
  return d.norm() > 0.0 ? Vec2(d.normalized()) : Vec2(Vec2::UnitX());
}

}  // namespace

double turning_angle(const Polygon2& polygon, size_t i) {
  const size_t n = polygon.size();
  const Vec2 in = polygon[i] - polygon[(i + n - 1) % n];
  const Vec2 out = polygon[(i + 1) % n] - polygon[i];
  if (in.norm() == 0.0 || out.norm() == 0.0) return 0.0;
  return std::atan2(std::abs(cross2(in, out)), in.dot(out));
}

TruedOutline true_outline(const Polygon2& polygon, const std::vector<bool>& keep,
                          const std::vector<bool>& corner, double tolerance,
                          double sample_spacing) {
  const size_t n = polygon.size();
  TruedOutline out;
  if (tolerance <= 0.0 || n < 3) {
    out.points = polygon;
    for (size_t i = 0; i < n; ++i) {
      out.source.push_back(static_cast<int>(i));
      out.edge_source.push_back(static_cast<int>(i));
    }
    return out;
  }
  std::vector<bool> kept(n, false);
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    kept[i] = keep[i] || corner[i];
    any = any || kept[i];
  }
  if (!any) kept[0] = true;
  const double spacing = sample_spacing > 0.0 ? sample_spacing : 1.0;
  size_t first = 0;
  while (!kept[first]) ++first;
  size_t i = first;
  do {
    std::vector<int> idx = {static_cast<int>(i)};
    size_t j = (i + 1) % n;
    while (!kept[j]) {
      idx.push_back(static_cast<int>(j));
      j = (j + 1) % n;
    }
    idx.push_back(static_cast<int>(j));
    // At a smooth kept point both stretches share one tangent, from the polygon around it.
    const double reach = 5.0 * spacing;
    const Vec2 start = corner[i] ? Vec2(Vec2::Zero()) : smooth_tangent(polygon, i, reach);
    const Vec2 end = corner[j] ? Vec2(Vec2::Zero()) : smooth_tangent(polygon, j, reach);
    Stretch(polygon, std::move(idx), start, end, tolerance, spacing).emit(out);
    i = j;
  } while (i != first);
  return out;
}

}  // namespace tightfit
