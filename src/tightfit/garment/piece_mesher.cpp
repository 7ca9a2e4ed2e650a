#include "tightfit/garment/piece_mesher.hpp"

#include "tightfit/garment/boundary_chords.hpp"

#include "tightfit/common/planar.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace tightfit {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexInfo {
  int id = -1;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
struct FaceInfo {
  int nesting = -1;  // number of constrained edges crossed from the infinite face
};
using Fb =
    CGAL::Triangulation_face_base_with_info_2<FaceInfo, K,
                                              CGAL::Constrained_triangulation_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

bool inside_loop(const std::vector<Vec2>& p, const Vec2& q) {
  return inside_polygon(
      p.size(), [&p](size_t i) { return p[i]; }, q);
}

double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - q).norm();
}

/// The piece's boundary loops: the outer one first, then the holes, as one list of
/// points with the loop of each point's successor.
struct Loops {
  std::vector<Vec2> points;
  std::vector<int> next;  // per point: the next point along its loop

  void add(const std::vector<Vec2>& loop) {
    const int first = static_cast<int>(points.size()), n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i) {
      points.push_back(loop[i]);
      next.push_back(first + (i + 1) % n);
    }
  }
  int size() const { return static_cast<int>(points.size()); }
};

/// Constrained Delaunay triangulation of the boundary loops and the interior points;
/// the triangles inside the piece (inside the outer loop, outside every hole), each
/// rotated to start at its smallest index, sorted.
std::vector<std::array<int, 3>> triangulate(const Loops& loops, const std::vector<Vec2>& interior) {
  const int nb = loops.size();
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles(nb);
  for (int i = 0; i < nb; ++i) {
    handles[i] = cdt.insert(K::Point_2(loops.points[i].x(), loops.points[i].y()));
    if (handles[i]->info().id >= 0)
      throw std::invalid_argument("mesh_piece: two boundary vertices coincide");
    handles[i]->info().id = i;
  }
  try {
    for (int i = 0; i < nb; ++i) cdt.insert_constraint(handles[i], handles[loops.next[i]]);
  } catch (const std::exception&) {
    throw std::invalid_argument("mesh_piece: the boundary crosses itself");
  }
  if (static_cast<int>(cdt.number_of_vertices()) != nb)
    throw std::invalid_argument("mesh_piece: the boundary touches itself");
  for (size_t i = 0; i < interior.size(); ++i) {
    const auto v = cdt.insert(K::Point_2(interior[i].x(), interior[i].y()));
    v->info().id = nb + static_cast<int>(i);
  }
  // The domain: faces reached from the infinite face by crossing one constrained edge
  // (exact, unlike testing face centroids, which fails for slivers along straight runs).
  std::vector<Cdt::Face_handle> front{cdt.infinite_face()}, next;
  cdt.infinite_face()->info().nesting = 0;
  for (int level = 0; !front.empty(); ++level) {
    std::vector<Cdt::Face_handle> queue = front;
    next.clear();
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.back();
      queue.pop_back();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle g = f->neighbor(i);
        if (g->info().nesting >= 0) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          next.push_back(g);
        } else {
          g->info().nesting = level;
          queue.push_back(g);
        }
      }
    }
    front.clear();
    for (const auto& g : next)
      if (g->info().nesting < 0) {
        g->info().nesting = level + 1;
        front.push_back(g);
      }
  }
  std::vector<std::array<int, 3>> tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info().nesting % 2 != 1) continue;
    std::array<int, 3> t{f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    tris.push_back(t);
  }
  std::sort(tris.begin(), tris.end());
  return tris;
}

}  // namespace

PieceMesh mesh_piece(const Points2& boundary_points, double h, int smoothing_iterations) {
  return mesh_piece(boundary_points, {}, h, smoothing_iterations);
}

PieceMesh mesh_piece(const Points2& boundary_points, const std::vector<Points2>& hole_points,
                     double h, int smoothing_iterations) {
  const int n_outer = static_cast<int>(boundary_points.rows());
  if (n_outer < 3) throw std::invalid_argument("mesh_piece: a boundary needs at least 3 vertices");
  if (!(h > 0)) throw std::invalid_argument("mesh_piece: edge length must be positive");
  auto to_vector = [](const Points2& p) {
    std::vector<Vec2> v(static_cast<size_t>(p.rows()));
    for (Eigen::Index i = 0; i < p.rows(); ++i) v[static_cast<size_t>(i)] = p.row(i).transpose();
    return v;
  };
  const std::vector<Vec2> outer = to_vector(boundary_points);
  if (signed_area(outer) <= 0)
    throw std::invalid_argument("mesh_piece: the boundary is not counter-clockwise");
  Loops loops;
  loops.add(outer);
  std::vector<std::vector<Vec2>> holes;
  for (size_t k = 0; k < hole_points.size(); ++k) {
    const std::string which = "mesh_piece: hole " + std::to_string(k + 1);
    if (hole_points[k].rows() < 3)
      throw std::invalid_argument(which + " needs at least 3 vertices");
    holes.push_back(to_vector(hole_points[k]));
    if (signed_area(holes.back()) >= 0) throw std::invalid_argument(which + " is not clockwise");
    for (const Vec2& q : holes.back())
      if (!inside_loop(outer, q))
        throw std::invalid_argument(which + " is not inside the outer boundary");
    loops.add(holes.back());
  }
  const int nb = loops.size();
  const std::vector<Vec2>& boundary = loops.points;
  auto in_piece = [&](const Vec2& q) {
    if (!inside_loop(outer, q)) return false;
    for (const auto& hole : holes)
      if (inside_loop(hole, q)) return false;
    return true;
  };

  // Lattice points inside, at least h/2 from the boundary.
  Vec2 lo = boundary[0], hi = boundary[0];
  for (const Vec2& p : outer) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::vector<Vec2> interior;
  const double dy = h * std::sqrt(3.0) / 2.0;
  for (int row = 0; lo.y() + (row + 0.5) * dy < hi.y(); ++row) {
    const double y = lo.y() + (row + 0.5) * dy;
    for (double x = lo.x() + (row % 2 == 0 ? 0.5 : 1.0) * h; x < hi.x(); x += h) {
      const Vec2 q(x, y);
      if (!in_piece(q)) continue;
      double d = std::numeric_limits<double>::infinity();
      for (int i = 0; i < nb && d >= 0.5 * h; ++i)
        d = std::min(d, segment_distance(q, boundary[i], boundary[loops.next[i]]));
      if (d >= 0.5 * h) interior.push_back(q);
    }
  }

  std::vector<std::array<int, 3>> tris = triangulate(loops, interior);
  auto point = [&](int i) -> const Vec2& { return i < nb ? boundary[i] : interior[i - nb]; };
  for (int it = 0; it < smoothing_iterations && !interior.empty(); ++it) {
    // Optimal-Delaunay step: each interior vertex to Σ|T| c_T / Σ|T| over its triangles.
    std::vector<Vec2> sum(interior.size(), Vec2::Zero());
    std::vector<double> weight(interior.size(), 0.0);
    std::vector<std::vector<int>> star(interior.size());
    for (size_t t = 0; t < tris.size(); ++t) {
      const Vec2 a = point(tris[t][0]), b = point(tris[t][1]), c = point(tris[t][2]);
      const double area2 = cross2(b - a, c - a);
      if (area2 <= 0) continue;
      const Vec2 ab = b - a, ac = c - a;
      const Vec2 cc = a + (ac.squaredNorm() * Vec2(ab.y(), -ab.x()) -
                           ab.squaredNorm() * Vec2(ac.y(), -ac.x())) /
                              (-2.0 * cross2(ab, ac));
      for (int k = 0; k < 3; ++k)
        if (tris[t][k] >= nb) {
          sum[tris[t][k] - nb] += 0.5 * area2 * cc;
          weight[tris[t][k] - nb] += 0.5 * area2;
          star[tris[t][k] - nb].push_back(static_cast<int>(t));
        }
    }
    // A move is kept when it folds nothing and does not lower the smallest angle of the
    // vertex's triangles (near a concave stretch of boundary the circumcentres lie
    // outside, and the step would push the vertex onto the boundary).
    auto star_min_angle = [&](const std::vector<int>& triangles) {
      double smallest = std::numbers::pi;
      for (int t : triangles)
        for (int k = 0; k < 3; ++k) {
          const Vec2 u = point(tris[t][(k + 1) % 3]) - point(tris[t][k]);
          const Vec2 w = point(tris[t][(k + 2) % 3]) - point(tris[t][k]);
          smallest = std::min(smallest, std::atan2(std::abs(cross2(u, w)), u.dot(w)));
        }
      return smallest;
    };
    for (size_t v = 0; v < interior.size(); ++v) {
      if (weight[v] <= 0) continue;
      const Vec2 old = interior[v];
      const double angle_before = star_min_angle(star[v]);
      interior[v] = sum[v] / weight[v];
      bool folds = false;
      for (int t : star[v]) {
        const Vec2 a = point(tris[t][0]), b = point(tris[t][1]), c = point(tris[t][2]);
        if (cross2(b - a, c - a) <= 1e-3 * h * h) folds = true;
      }
      if (folds || star_min_angle(star[v]) < angle_before) interior[v] = old;
    }
    tris = triangulate(loops, interior);
  }

  PieceMesh out;
  out.vertices.resize(nb + static_cast<Eigen::Index>(interior.size()), 2);
  for (int i = 0; i < nb; ++i) out.vertices.row(i) = boundary[i].transpose();
  for (size_t i = 0; i < interior.size(); ++i)
    out.vertices.row(nb + static_cast<Eigen::Index>(i)) = interior[i].transpose();
  out.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i)
    for (int c = 0; c < 3; ++c) out.triangles(static_cast<Eigen::Index>(i), c) = tris[i][c];
  split_boundary_chords(out, nb);
  return out;
}

double min_angle_deg(const Points2& x, const Triangles& t) {
  double best = t.rows() > 0 ? 180.0 : 0.0;
  for (Eigen::Index f = 0; f < t.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = x.row(t(f, (k + 1) % 3)) - x.row(t(f, k));
      const Vec2 b = x.row(t(f, (k + 2) % 3)) - x.row(t(f, k));
      best = std::min(best, angle_between_deg(a, b));
    }
  return best;
}

}  // namespace tightfit
