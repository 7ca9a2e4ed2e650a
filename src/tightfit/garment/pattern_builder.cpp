#include "tightfit/garment/pattern_builder.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/mesh_budget.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/garment/boundary_resampling.hpp"
#include "tightfit/garment/piece_mesher.hpp"
#include "tightfit/garment/triangle_geometry.hpp"
#include "tightfit/garment/triangle_locator.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << 100.0 * x << " %";
  return s.str();
}

int loop_vertex(const LayoutPanel& panel, int i) {
  const int n = static_cast<int>(panel.boundary.size());
  return panel.boundary[((i % n) + n) % n];
}

double flat_length(const LayoutPanel& panel, const BoundarySegment& s, const Points2& flat,
                   const Mat2& linear) {
  double len = 0.0;
  for (int e = 0; e < s.count; ++e)
    len += (linear * (flat.row(loop_vertex(panel, s.first + e + 1)) -
                      flat.row(loop_vertex(panel, s.first + e)))
                         .transpose())
               .norm();
  return len;
}

double length_3d(const LayoutPanel& panel, const BoundarySegment& s) {
  double len = 0.0;
  for (int e = 0; e < s.count; ++e)
    len += (panel.mesh.vertices.row(loop_vertex(panel, s.first + e + 1)) -
            panel.mesh.vertices.row(loop_vertex(panel, s.first + e)))
               .norm();
  return len;
}

/// Turning angle (degrees, 0 for a straight run) of the flattened boundary at loop
/// position i.
double turning_angle_deg(const LayoutPanel& panel, const Points2& flat, int i) {
  const Vec2 a = flat.row(loop_vertex(panel, i)) - flat.row(loop_vertex(panel, i - 1));
  const Vec2 b = flat.row(loop_vertex(panel, i + 1)) - flat.row(loop_vertex(panel, i));
  return angle_between_deg(a, b);
}

/// Grain direction of a flattened panel in flat coordinates (unit).
Vec2 grain_direction(const LayoutPanel& panel, const Points2& flat, const PatternOptions& options) {
  const TriMesh& m = panel.mesh;
  if (options.grain) {
    Vec2 sum = Vec2::Zero();
    for (int f = 0; f < m.num_faces(); ++f) {
      const Vec3 p0 = m.vertices.row(m.faces(f, 0)), p1 = m.vertices.row(m.faces(f, 1)),
                 p2 = m.vertices.row(m.faces(f, 2));
      Eigen::Matrix<double, 3, 2> E;
      E << p1 - p0, p2 - p0;
      const double area = triangle_area(p0, p1, p2);
      if (area <= 0) continue;
      // Tangential part of the grain in edge coordinates, mapped to the flat triangle.
      const Vec2 ab = (E.transpose() * E).ldlt().solve(E.transpose() * *options.grain);
      const Vec2 q0 = flat.row(m.faces(f, 0)), q1 = flat.row(m.faces(f, 1)),
                 q2 = flat.row(m.faces(f, 2));
      sum += area * (ab.x() * (q1 - q0) + ab.y() * (q2 - q0));
    }
    if (sum.norm() > 0) return sum.normalized();
    // The grain is normal to the whole panel: fall back to the principal axis.
  }
  // Longest principal axis of the flat triangles (area-weighted centroid second moments).
  double area = 0.0;
  Vec2 c = Vec2::Zero();
  Mat2 second = Mat2::Zero();
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec2 q0 = flat.row(m.faces(f, 0)), q1 = flat.row(m.faces(f, 1)),
               q2 = flat.row(m.faces(f, 2));
    const double a = std::abs(signed_area(q0, q1, q2));
    for (const Vec2& q : {q0, q1, q2}) {
      c += a / 3.0 * q;
      second += a / 3.0 * q * q.transpose();
    }
    area += a;
  }
  c /= area;
  const Mat2 cov = second / area - c * c.transpose();
  Eigen::SelfAdjointEigenSolver<Mat2> eig(cov);
  Vec2 d = eig.eigenvectors().col(1);
  if (d.y() < 0 || (d.y() == 0 && d.x() < 0)) d = -d;
  return d;
}

/// Where a point of the flattened panel (flat coordinates, m) lies on the panel: the
/// triangle containing it, or outside the flat panel the nearest one with weights
/// extrapolated linearly.
PanelPoint locate_flat(const TriangleLocator& locator, const Vec2& q) {
  int f = locator.containing(q);
  if (f < 0) f = locator.nearest(q);
  return {f, locator.weights(f, q)};
}

/// Loop positions first … first + count of a run as panel vertex indices.
std::vector<int> run_path(const LayoutPanel& panel, const BoundarySegment& s) {
  std::vector<int> path;
  for (int e = 0; e <= s.count; ++e) path.push_back(loop_vertex(panel, s.first + e));
  return path;
}

/// A closed loop of panel vertices as a path back to its start.
std::vector<int> closed_path(const std::vector<int>& loop) {
  std::vector<int> path = loop;
  path.push_back(loop.front());
  return path;
}

/// Length (m) of a closed loop of flattened vertices after the piece's linear map.
double flat_loop_length(const std::vector<int>& loop, const Points2& flat, const Mat2& linear) {
  double len = 0.0;
  for (size_t e = 0; e < loop.size(); ++e)
    len +=
        (linear * (flat.row(loop[(e + 1) % loop.size()]) - flat.row(loop[e])).transpose()).norm();
  return len;
}

/// All boundary loops of a panel: the outer one, then the holes.
std::vector<std::vector<int>> panel_loops(const LayoutPanel& panel) {
  std::vector<std::vector<int>> loops{panel.boundary};
  for (const PanelHole& hole : panel.holes) loops.push_back(hole.loop);
  return loops;
}

/// The boundary runs of the pieces: the layout's boundary segments, open ones further
/// split at sharp turns of the flattened boundary (piece corners that are not seam ends).
struct PieceRuns {
  std::vector<std::vector<BoundarySegment>> runs;  ///< per panel
  std::vector<std::vector<int>> first_run;         ///< per panel and layout segment: its first run
  std::vector<std::vector<int>> count;             ///< per panel and run: its edges in the piece
  /// Per panel and run: the piece boundary vertex it starts at.
  std::vector<std::vector<int>> run_start;
};

/// Flattens and checks each panel (independent: on the threads; the error of the first
/// failing panel is the one reported), then checks the mesh budget of the pieces.
void flatten_panels(const Layout& layout, const PatternOptions& options, PatternBuild& out) {
  const int np = static_cast<int>(layout.panels.size());
  out.maps.resize(np);
  parallel_for(
      np,
      [&](std::int64_t i) {
        const int p = static_cast<int>(i);
        const LayoutPanel& panel = layout.panels[p];
        const std::vector<std::vector<int>> loops = panel_loops(panel);
        Flattening flat = flatten_panel(panel.mesh, loops, options.flatten);
        const std::string why = find_overlap(panel.mesh, loops, flat.uv);
        if (!why.empty())
          throw InputError(layout.source, "panel \"" + panel.name +
                                              "\" overlaps itself when flattened (" + why +
                                              "); split it with a divider into less curved panels");
        if (flat.report.area_error > layout.area_tolerance)
          throw InputError(layout.source,
                           "panel \"" + panel.name +
                               "\" is too curved to flatten: its flat area differs from "
                               "its area on the body by " +
                               percent(flat.report.area_error) + " (area_tolerance " +
                               percent(layout.area_tolerance) +
                               "); split it with a divider into less curved panels");
        PieceMap& map = out.maps[p];
        map.panel = p;
        map.flat = std::move(flat.uv);
        map.distortion = flat.report;
        map.arap_iterations = flat.iterations;
      },
      2);
  double flat_area = 0.0;
  for (const PieceMap& map : out.maps) flat_area += map.distortion.area_2d;
  check_mesh_budget(flat_area, options.edge_length, "pattern pieces", layout.source + ": pattern");
}

/// The seam sides after flattening, before scaling (InputError when they differ too much).
void check_seam_sides(const Layout& layout, double h, PatternBuild& out) {
  for (const LayoutSeam& seam : layout.seams) {
    const LayoutPanel& pa = layout.panels[seam.panel_a];
    const LayoutPanel& pb = layout.panels[seam.panel_b];
    SeamReport r;
    r.name = seam.name;
    r.length_3d = length_3d(pa, pa.segments[seam.segment_a]);
    r.length_a =
        flat_length(pa, pa.segments[seam.segment_a], out.maps[seam.panel_a].flat, Mat2::Identity());
    r.length_b =
        flat_length(pb, pb.segments[seam.segment_b], out.maps[seam.panel_b].flat, Mat2::Identity());
    r.relative_difference = std::abs(r.length_a - r.length_b) / std::max(r.length_a, r.length_b);
    // A difference below one pattern edge is below what the pattern mesh resolves (and
    // a few millimetres of ease on a short seam): only longer ones are checked.
    if (r.relative_difference > layout.seam_tolerance && std::abs(r.length_a - r.length_b) > h)
      throw InputError(
          layout.source,
          "seam \"" + seam.name + "\" (" + std::to_string(r.length_3d) +
              " m on the body): its sides are " + std::to_string(r.length_a) + " m and " +
              std::to_string(r.length_b) + " m long after flattening, a difference of " +
              percent(r.relative_difference) + " (seam_tolerance " +
              percent(layout.seam_tolerance) +
              ", and more than the pattern edge length); the panels are too curved for "
              "this seam: add dividers");
    out.seams.push_back(r);
  }
}

/// Each piece's grain frame and scale: its linear map and offset.
void place_in_grain_frames(const Layout& layout, const PatternOptions& options, PatternBuild& out) {
  for (size_t p = 0; p < layout.panels.size(); ++p) {
    PieceMap& map = out.maps[p];
    const Vec2 d = grain_direction(layout.panels[p], map.flat, options);
    Mat2 rot;
    rot << d.y(), -d.x(), d.x(), d.y();  // maps d to +y
    const PieceScale& s = options.scale_of(layout.panels[p].name);
    map.linear = Eigen::DiagonalMatrix<double, 2>(s.across, s.along) * rot;
    const Points2 moved = map.flat * map.linear.transpose();
    map.offset = -moved.colwise().minCoeff().transpose();
  }
}

/// The runs of PieceRuns (runs, first_run). Seams stay whole so that both sides are
/// sampled alike.
void split_into_runs(const Layout& layout, const PatternOptions& options, const PatternBuild& out,
                     PieceRuns& r) {
  const size_t np = layout.panels.size();
  r.runs.resize(np);
  r.first_run.resize(np);
  for (size_t p = 0; p < np; ++p) {
    const LayoutPanel& panel = layout.panels[p];
    for (const BoundarySegment& segment : panel.segments) {
      r.first_run[p].push_back(static_cast<int>(r.runs[p].size()));
      BoundarySegment s = segment;
      if (s.seam >= 0) {
        r.runs[p].push_back(s);
        continue;
      }
      auto sharp = [&](int i) {
        return turning_angle_deg(panel, out.maps[p].flat, i) > options.corner_angle_deg;
      };
      if (panel.segments.size() == 1)  // a whole open loop: start at a corner if it has one
        for (int i = 0; i < s.count; ++i)
          if (sharp(s.first + i)) {
            s.first += i;
            break;
          }
      for (const LoopRun& cut : cut_run({s.first, s.count}, sharp)) {
        BoundarySegment run = s;
        run.first = cut.first;
        run.count = cut.count;
        r.runs[p].push_back(run);
      }
    }
  }
}

/// The edge count of every run at the edge length h: seams shared by both sides (with
/// their vertex counts in out.seams).
void count_run_edges(const Layout& layout, double h, PatternBuild& out, PieceRuns& r) {
  const size_t np = layout.panels.size();
  r.count.resize(np);
  auto min_count = [&](int p) { return min_edge_count(static_cast<int>(r.runs[p].size())); };
  for (size_t p = 0; p < np; ++p)
    for (const BoundarySegment& run : r.runs[p]) {
      const double len = flat_length(layout.panels[p], run, out.maps[p].flat, out.maps[p].linear);
      r.count[p].push_back(edge_count(len, h, min_count(static_cast<int>(p))));
    }
  for (size_t k = 0; k < layout.seams.size(); ++k) {
    const LayoutSeam& seam = layout.seams[k];
    const int ra = r.first_run[seam.panel_a][seam.segment_a],
              rb = r.first_run[seam.panel_b][seam.segment_b];
    const double la = flat_length(layout.panels[seam.panel_a], r.runs[seam.panel_a][ra],
                                  out.maps[seam.panel_a].flat, out.maps[seam.panel_a].linear);
    const double lb = flat_length(layout.panels[seam.panel_b], r.runs[seam.panel_b][rb],
                                  out.maps[seam.panel_b].flat, out.maps[seam.panel_b].linear);
    const int n = seam_edge_count(la, lb, h, min_count(seam.panel_a), min_count(seam.panel_b));
    r.count[seam.panel_a][ra] = r.count[seam.panel_b][rb] = n;
    out.seams[k].vertices = n + 1;
  }
}

/// The piece of panel p: its boundary resampled run by run (and each hole as one closed
/// run), meshed in 2D, every vertex located on the panel; run_start[p] filled.
void mesh_panel_piece(const Layout& layout, int p, const PatternOptions& options, PatternBuild& out,
                      PieceRuns& r) {
  const double h = options.edge_length;
  const LayoutPanel& panel = layout.panels[p];
  PieceMap& map = out.maps[p];
  const SurfaceTopology topo(panel.mesh.faces, panel.mesh.num_vertices());
  std::vector<PanelPoint> boundary_location;
  std::vector<Vec2> boundary_points;
  // A sample on the panel's boundary edge i → j at parameter t.
  auto add_sample = [&](int i, int j, double t) {
    const int f = topo.edge_faces(topo.find_edge(i, j))[0];
    PanelPoint loc{f, Vec3::Zero()};
    for (int c = 0; c < 3; ++c) {
      if (panel.mesh.faces(f, c) == i) loc.weights[c] = 1.0 - t;
      if (panel.mesh.faces(f, c) == j) loc.weights[c] = t;
    }
    boundary_location.push_back(loc);
    const Vec2 q = (1.0 - t) * map.flat.row(i).transpose() + t * map.flat.row(j).transpose();
    boundary_points.push_back(map.linear * q + map.offset);
  };
  auto polygon_of = [&](size_t from) {
    return polygon_rows(std::vector<Vec2>(
        boundary_points.begin() + static_cast<std::ptrdiff_t>(from), boundary_points.end()));
  };
  for (size_t ri = 0; ri < r.runs[p].size(); ++ri) {
    r.run_start[p].push_back(static_cast<int>(boundary_points.size()));
    const BoundarySegment& run = r.runs[p][ri];
    for (const ArcPoint& b :
         sample_arc(cumulative_lengths(panel.mesh.vertices, run_path(panel, run)), r.count[p][ri]))
      add_sample(loop_vertex(panel, run.first + b.edge), loop_vertex(panel, run.first + b.edge + 1),
                 b.t);
  }
  const Points2 polygon = polygon_of(0);
  // Openings: each hole loop resampled as one closed run at the edge length.
  std::vector<Points2> hole_polygons;
  std::vector<std::vector<int>> hole_vertices;
  for (const PanelHole& hole : panel.holes) {
    const size_t from = boundary_points.size();
    const int n_hole =
        edge_count(flat_loop_length(hole.loop, map.flat, map.linear), h, min_edge_count(1));
    const int m = static_cast<int>(hole.loop.size());
    for (const ArcPoint& b :
         sample_arc(cumulative_lengths(panel.mesh.vertices, closed_path(hole.loop)), n_hole))
      add_sample(hole.loop[b.edge % m], hole.loop[(b.edge + 1) % m], b.t);
    hole_polygons.push_back(polygon_of(from));
    std::vector<int> vertices(static_cast<size_t>(n_hole));
    for (int k = 0; k < n_hole; ++k) vertices[static_cast<size_t>(k)] = static_cast<int>(from) + k;
    hole_vertices.push_back(std::move(vertices));
  }
  PieceMesh mesh;
  try {
    mesh = mesh_piece(polygon, hole_polygons, h, options.smoothing_iterations);
  } catch (const std::invalid_argument& e) {
    throw InputError(layout.source, "piece \"" + panel.name + "\" cannot be meshed (" + e.what() +
                                        "); try a smaller edge_length");
  }
  PatternPiece piece;
  piece.name = panel.name;
  piece.rest = std::move(mesh.vertices);
  piece.triangles = std::move(mesh.triangles);
  for (Eigen::Index i = 0; i < polygon.rows(); ++i) piece.boundary.push_back(static_cast<int>(i));
  piece.holes = hole_vertices;
  const auto nb = static_cast<Eigen::Index>(boundary_points.size());
  if (r.runs[p].size() > 1 || r.runs[p][0].seam >= 0) piece.corners = r.run_start[p];
  piece.grain = Vec2::UnitY();
  map.location = boundary_location;
  const TriangleLocator locator(panel.mesh.faces, map.flat);
  for (Eigen::Index v = nb; v < piece.rest.rows(); ++v)
    map.location.push_back(locate_in_panel(locator, map, piece.rest.row(v).transpose()));
  out.pattern.pieces.push_back(std::move(piece));
}

/// The pattern's seams and pinned boundaries in piece vertex indices.
void connect_seams_and_pins(const Layout& layout, const PieceRuns& r, PatternBuild& out) {
  const int np = static_cast<int>(layout.panels.size());
  // The boundary vertices of the runs [r0, r1) of panel p, both ends included.
  auto run_vertices = [&](int p, int r0, int r1) {
    int n = 0;
    for (int k = r0; k < r1; ++k) n += r.count[p][k];
    const int nb = static_cast<int>(out.pattern.pieces[p].boundary.size());
    std::vector<int> v;
    for (int k = 0; k <= n; ++k) v.push_back((r.run_start[p][r0] + k) % nb);
    return v;
  };
  for (const LayoutSeam& seam : layout.seams) {
    const int ra = r.first_run[seam.panel_a][seam.segment_a],
              rb = r.first_run[seam.panel_b][seam.segment_b];
    Seam s;
    s.name = seam.name;
    s.a = {seam.panel_a, run_vertices(seam.panel_a, ra, ra + 1)};
    s.b = {seam.panel_b, run_vertices(seam.panel_b, rb, rb + 1)};
    std::reverse(s.b.vertices.begin(), s.b.vertices.end());
    out.pattern.seams.push_back(std::move(s));
  }
  for (int p = 0; p < np; ++p)
    for (size_t si = 0; si < layout.panels[p].segments.size(); ++si) {
      const BoundarySegment& s = layout.panels[p].segments[si];
      if (s.seam >= 0 || s.pin < 0) continue;
      const int r1 = si + 1 < r.first_run[p].size() ? r.first_run[p][si + 1]
                                                    : static_cast<int>(r.runs[p].size());
      std::vector<int> v = run_vertices(p, r.first_run[p][si], r1);
      if (layout.panels[p].segments.size() == 1) v.pop_back();  // whole loop: no repeat
      out.pattern.pinned.push_back({layout.pin_names[s.pin], p, std::move(v)});
    }
  for (int p = 0; p < np; ++p)
    for (size_t k = 0; k < layout.panels[p].holes.size(); ++k)
      if (const int pin = layout.panels[p].holes[k].pin; pin >= 0)
        out.pattern.pinned.push_back({layout.pin_names[pin], p, out.pattern.pieces[p].holes[k]});
}

}  // namespace

PatternBuild build_pattern(const Layout& layout, const PatternOptions& options) {
  const double h = options.edge_length;
  if (!(h > 0)) throw std::invalid_argument("build_pattern: edge_length must be positive");
  PatternBuild out;
  flatten_panels(layout, options, out);
  check_seam_sides(layout, h, out);
  place_in_grain_frames(layout, options, out);
  PieceRuns runs;
  split_into_runs(layout, options, out, runs);
  count_run_edges(layout, h, out, runs);
  runs.run_start.resize(layout.panels.size());
  for (int p = 0; p < static_cast<int>(layout.panels.size()); ++p)
    mesh_panel_piece(layout, p, options, out, runs);
  connect_seams_and_pins(layout, runs, out);
  return out;
}

Vec3 panel_position(const Layout& layout, const PieceMap& map, const PanelPoint& point) {
  const TriMesh& m = layout.panels[map.panel].mesh;
  Vec3 x = Vec3::Zero();
  for (int c = 0; c < 3; ++c)
    x += point.weights[c] * m.vertices.row(m.faces(point.face, c)).transpose();
  return x;
}

PanelPoint locate_in_panel(const TriangleLocator& locator, const PieceMap& map,
                           const Vec2& piece_point) {
  return locate_flat(locator, map.linear.inverse() * (piece_point - map.offset));
}

}  // namespace tightfit
