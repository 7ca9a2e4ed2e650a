#include "tightfit/garment/ease_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tightfit/geometry/plane_loops.hpp"

namespace tightfit {
namespace {

/// Signed distances of the rows of `x` to the plane of `level` (m).
std::vector<double> plane_side(const Points3& x, const MeasurementLevel& level) {
  const Vec3 n = level.normal.normalized();
  std::vector<double> side(static_cast<size_t>(x.rows()));
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    side[static_cast<size_t>(i)] = n.dot(x.row(i).transpose() - level.point);
  return side;
}

/// The farthest crossing point of loop `loop` from `point` (m).
double loop_reach(const TriMesh& mesh, const PlaneCut& cut, int loop, const Vec3& point) {
  double reach = 0.0;
  for (size_t i = 0; i < cut.edges.size(); ++i)
    if (cut.loop[i] == loop)
      reach = std::max(reach, (crossing_point(mesh, cut, static_cast<int>(i)) - point).norm());
  return reach;
}

/// The corner of garment triangle `f` at garment vertex `v`.
int corner_of(const Garment& garment, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (garment.topology->garment_triangles(f, k) == v) return k;
  return -1;  // not reached: a crossed edge of a face has both ends among its corners
}

/// The rest (pattern) position of crossed edge `i`'s crossing point, in face `f`.
Vec2 rest_crossing(const Garment& garment, const Points2& rest, const PlaneCut& cut, int f, int i) {
  const auto [a, b] = cut.edges[static_cast<size_t>(i)];
  const double t = cut.t[static_cast<size_t>(i)];
  const int pa = garment.topology->pattern_triangles(f, corner_of(garment, f, a));
  const int pb = garment.topology->pattern_triangles(f, corner_of(garment, f, b));
  return (1.0 - t) * rest.row(pa).transpose() + t * rest.row(pb).transpose();
}

LevelMeasurement measure_level(const MeasurementLevel& level, const TriMesh& body,
                               const TriMesh& fitted, const Garment& garment, const Points2& rest) {
  LevelMeasurement m;
  m.level = level;
  const Vec3 n = level.normal.normalized();
  const PlaneCut body_cut = cut_by_plane(body, plane_side(body.vertices, level));
  if (body_cut.edges.empty()) {
    m.skipped = "the plane misses the body";
    return m;
  }
  const NearestCutLoop around = nearest_cut_loop(body, body_cut, level.point, n);
  if (!around.encloses) {
    // E.g. a level on an arm bone of a body cropped to the legs: its plane cuts the legs.
    m.skipped = "the level's point is not inside the body's cross-section there";
    return m;
  }
  const int body_loop = around.loop;
  const double body_reach = loop_reach(body, body_cut, body_loop, level.point);
  const PlaneCut cut = cut_by_plane(fitted, plane_side(fitted.vertices, level));
  const NearestCutLoop loop = nearest_cut_loop(fitted, cut, level.point, n);
  // The garment reaches the level when its cut there lies about on the body's loop
  // (within a tenth of the loop's size: the garment lies on the body).
  m.reached = loop.loop >= 0 && loop.distance <= 1.1 * body_reach;
  if (!m.reached) {
    m.skipped = "the garment does not reach this level";
    return m;
  }
  if (!loop.encloses || !cut.closed[static_cast<size_t>(loop.loop)]) {
    m.skipped =
        "the garment does not go all the way around here (its edge or an opening crosses the "
        "level)";
    return m;
  }
  m.body_circumference = cut_loop_length(body, body_cut, body_loop);
  m.garment_circumference = cut_loop_length(fitted, cut, loop.loop);
  const int num_pieces = static_cast<int>(garment.pattern.pieces.size());
  std::vector<double> width(static_cast<size_t>(num_pieces), 0.0);
  std::vector<char> has(static_cast<size_t>(num_pieces), 0);
  for (const PlaneCut::Segment& s : cut.segments) {
    if (cut.loop[static_cast<size_t>(s.a)] != loop.loop) continue;
    const double length = (rest_crossing(garment, rest, cut, s.face, s.b) -
                           rest_crossing(garment, rest, cut, s.face, s.a))
                              .norm();
    const auto piece =
        static_cast<size_t>(garment.topology->triangle_piece[static_cast<size_t>(s.face)]);
    width[piece] += length;
    has[piece] = 1;
    m.pattern_circumference += length;
  }
  for (int k = 0; k < num_pieces; ++k)
    if (has[static_cast<size_t>(k)])
      m.pieces.push_back(
          {garment.pattern.pieces[static_cast<size_t>(k)].name, width[static_cast<size_t>(k)]});
  return m;
}

/// `value` with `decimals` decimals ("-0" printed as "0").
std::string fixed(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  double rounded = std::round(value * scale) / scale;
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, rounded);
  return text;
}

}  // namespace

std::optional<double> body_circumference(const TriMesh& body, const MeasurementLevel& level) {
  const PlaneCut cut = cut_by_plane(body, plane_side(body.vertices, level));
  if (cut.edges.empty()) return std::nullopt;
  return cut_loop_length(body, cut,
                         nearest_cut_loop(body, cut, level.point, level.normal.normalized()).loop);
}

double LevelMeasurement::ease_percent() const {
  return body_circumference > 0.0
             ? (pattern_circumference - body_circumference) / body_circumference * 100.0
             : 0.0;
}

double LevelMeasurement::fitted_stretch() const {
  return pattern_circumference > 0.0 ? garment_circumference / pattern_circumference : 0.0;
}

EaseTable measure_ease(const std::vector<MeasurementLevel>& levels, const TriMesh& body,
                       const Garment& garment, const Points3& garment_positions) {
  const TriMesh fitted{garment_positions, garment.topology->garment_triangles};
  const Points2 rest = garment.rest_positions();
  EaseTable table;
  for (const MeasurementLevel& level : levels)
    table.levels.push_back(measure_level(level, body, fitted, garment, rest));
  return table;
}

EaseTable drop_uncovered(EaseTable table) {
  std::erase_if(table.levels, [](const LevelMeasurement& m) { return !m.reached; });
  return table;
}

std::map<std::string, std::vector<std::string>> ease_label_lines(const EaseTable& table) {
  std::map<std::string, std::vector<std::string>> lines;
  for (const LevelMeasurement& m : table.levels) {
    if (!m.skipped.empty()) continue;
    for (const PieceWidth& p : m.pieces) {
      std::string line = m.level.name;
      line += " ";
      line += fixed(m.body_circumference * 100.0, 1);
      line += " cm, piece ";
      line += fixed(p.width * 100.0, 1);
      line += " cm, ease ";
      line += fixed(m.ease_percent(), 0);
      line += " %";
      lines[p.piece].push_back(std::move(line));
    }
  }
  return lines;
}

}  // namespace tightfit
