// CGAL polygon-soup repair and hole filling of scanned bodies.
#include "tightfit/body/scan_repair.hpp"

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <tuple>
#include <utility>

#include "tightfit/body/cgal_surface_mesh.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using namespace cgal_surface;
using Polygon = std::vector<std::size_t>;
using FairingSolver = CGAL::Eigen_solver_traits<
    Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

std::string at(const Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), "(%.4g, %.4g, %.4g)", p.x(), p.y(), p.z());
  return buffer;
}

/// What orient_polygon_soup changed (CGAL's PMPPolygonSoupOrientationVisitor).
struct OrientationCounts {
  std::set<std::pair<std::size_t, std::size_t>> non_manifold_edges;
  std::set<std::size_t> non_manifold_vertices;
  std::size_t reversed = 0;
  std::size_t first_point = 0;  ///< a point of the first non-manifold element
  bool any_non_manifold = false;
};

struct OrientationVisitor : PMP::Default_orientation_visitor {
  OrientationCounts* counts;
  explicit OrientationVisitor(OrientationCounts* c) : counts(c) {}
  void non_manifold_edge(std::size_t a, std::size_t b, std::size_t) {
    note(a);
    counts->non_manifold_edges.insert(std::minmax(a, b));
  }
  void non_manifold_vertex(std::size_t v, std::size_t) {
    note(v);
    counts->non_manifold_vertices.insert(v);
  }
  void polygon_orientation_reversed(std::size_t) { ++counts->reversed; }
  void note(std::size_t v) {
    if (!counts->any_non_manifold) counts->first_point = v;
    counts->any_non_manifold = true;
  }
};

void append(std::string& text, std::size_t count, const std::string& what) {
  if (count == 0) return;
  text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + what;
}

/// The soup of `mesh` (indices checked, coordinates finite).
void to_soup(const TriMesh& mesh, const std::string& source, std::vector<Point>& points,
             std::vector<Polygon>& polygons) {
  const int n = mesh.num_vertices();
  points.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    if (!mesh.vertices.row(i).allFinite())
      throw InputError(
          source, "vertex " + std::to_string(i) + " has a coordinate that is not a finite number");
    points.emplace_back(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  }
  polygons.reserve(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Polygon polygon(3);
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.faces(f, c);
      if (v < 0 || v >= n)
        throw InputError(source, "face " + std::to_string(f) + " names vertex " +
                                     std::to_string(v) + ", which does not exist");
      polygon[c] = static_cast<std::size_t>(v);
    }
    polygons.push_back(std::move(polygon));
  }
}

std::size_t used_vertices(const std::vector<Polygon>& polygons, std::size_t n) {
  std::vector<char> used(n, 0);
  for (const Polygon& p : polygons)
    for (std::size_t v : p) used[v] = 1;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

/// Collapses or flips zero-area faces away; returns how many there were.
std::size_t remove_zero_area_faces(Mesh& mesh, const std::string& source) {
  auto degenerate = [&mesh] {
    std::vector<Mesh::Face_index> faces;
    for (Mesh::Face_index f : mesh.faces())
      if (PMP::is_degenerate_triangle_face(f, mesh)) faces.push_back(f);
    return faces;
  };
  const std::size_t count = degenerate().size();
  if (count == 0) return 0;
  const bool removed = PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  const std::vector<Mesh::Face_index> left = degenerate();
  if (!removed || !left.empty()) {
    const Vec3 p =
        left.empty() ? Vec3::Zero() : to_vec(mesh.point(mesh.target(mesh.halfedge(left[0]))));
    throw InputError(source, "the mesh has faces of zero area that could not be removed" +
                                 (left.empty() ? std::string()
                                               : " (" + std::to_string(left.size()) + ", one at " +
                                                     at(p) + ")"));
  }
  return count;
}

SurfaceHole measure_hole(const Mesh& mesh, Mesh::Halfedge_index border) {
  SurfaceHole hole;
  for (Mesh::Halfedge_index h : CGAL::halfedges_around_face(border, mesh)) {
    hole.boundary_length +=
        std::sqrt(CGAL::squared_distance(mesh.point(mesh.source(h)), mesh.point(mesh.target(h))));
    hole.center += to_vec(mesh.point(mesh.target(h)));
    ++hole.edges;
  }
  hole.center /= std::max(hole.edges, 1);
  return hole;
}

/// |Σ volume| of the faces plus flat fans over the remaining boundary loops.
double enclosed_volume(Mesh& mesh) {
  const CGAL::Bbox_3 box = PMP::bbox(mesh);
  const Vec3 origin(0.5 * (box.xmin() + box.xmax()), 0.5 * (box.ymin() + box.ymax()),
                    0.5 * (box.zmin() + box.zmax()));
  auto tet = [&origin](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (a - origin).dot((b - origin).cross(c - origin)) / 6.0;
  };
  double volume = 0.0;
  for (Mesh::Face_index f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    volume += tet(to_vec(mesh.point(mesh.source(h))), to_vec(mesh.point(mesh.target(h))),
                  to_vec(mesh.point(mesh.target(mesh.next(h)))));
  }
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (Mesh::Halfedge_index border : cycles) {
    const Vec3 center = measure_hole(mesh, border).center;
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_face(border, mesh))
      volume += tet(to_vec(mesh.point(mesh.source(h))), to_vec(mesh.point(mesh.target(h))), center);
  }
  return std::abs(volume);
}

}  // namespace

TriMesh repair_mesh_elements(const TriMesh& mesh, const std::string& source,
                             std::vector<std::string>& warnings) {
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  to_soup(mesh, source, points, polygons);
  const std::size_t used = used_vertices(polygons, points.size()), faces = polygons.size();
  PMP::repair_polygon_soup(points, polygons);
  if (polygons.empty())
    throw InputError(source,
                     "no face is left after removing duplicate faces and faces with a "
                     "repeated corner (the file has " +
                         std::to_string(faces) + ")");
  const std::size_t merged = used - points.size(), dropped = faces - polygons.size();
  OrientationCounts counts;
  PMP::orient_polygon_soup(points, polygons,
                           CGAL::parameters::visitor(OrientationVisitor(&counts)));
  const Vec3 first_non_manifold =
      counts.any_non_manifold ? to_vec(points[counts.first_point]) : Vec3::Zero();
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw InputError(source, "the mesh could not be made manifold (non-manifold elements near " +
                                 at(first_non_manifold) + ")");
  Mesh repaired;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, repaired);
  points = {};
  polygons = {};
  const std::size_t zero_area = remove_zero_area_faces(repaired, source);
  std::string changes;
  append(changes, merged, "duplicate vertices merged");
  append(changes, dropped, "duplicate faces or faces with a repeated corner removed");
  append(changes, zero_area, "faces of zero area removed");
  append(changes, counts.non_manifold_edges.size(), "non-manifold edges cut open");
  append(changes, counts.non_manifold_vertices.size(), "non-manifold vertices split");
  append(changes, counts.reversed, "faces turned to agree with their neighbours");
  if (!changes.empty())
    warnings.push_back(source + ": repaired the mesh: " + changes +
                       (counts.any_non_manifold
                            ? " (the first non-manifold element at " + at(first_non_manifold) + ")"
                            : std::string()));
  return from_cgal(repaired);
}

FilledSurface fill_small_holes(const TriMesh& surface, const std::string& source) {
  FilledSurface out;
  Mesh mesh = to_cgal(surface, source);
  out.area = PMP::area(mesh);
  out.hole_limit = std::sqrt(4.0 * std::numbers::pi * kSmallHoleAreaShare * out.area);
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (Mesh::Halfedge_index border : cycles) {
    SurfaceHole hole = measure_hole(mesh, border);
    std::vector<Mesh::Face_index> patch;
    if (hole.edges >= 3 && hole.boundary_length <= out.hole_limit) {
      std::vector<Mesh::Vertex_index> inner;
      hole.faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(
          mesh, border, std::back_inserter(patch), std::back_inserter(inner),
          CGAL::parameters::sparse_linear_solver(FairingSolver())));
    }
    (patch.empty() ? out.unfilled : out.filled).push_back(hole);
  }
  std::sort(out.unfilled.begin(), out.unfilled.end(),
            [](const SurfaceHole& a, const SurfaceHole& b) {
              return a.boundary_length > b.boundary_length;
            });
  out.enclosed_volume = enclosed_volume(mesh);
  out.mesh = from_cgal(mesh);
  return out;
}

}  // namespace tightfit
