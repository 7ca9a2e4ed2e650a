// CGAL's isotropic remeshing and feature detection (the cut is in crop_and_cap.cpp: the
// two are the body layer's heaviest templates, compiled apart so builds run them in parallel).
#include "tightfit/body/surface_remeshing.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tightfit/body/cgal_surface_mesh.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/self_intersection.hpp"

namespace tightfit {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using namespace cgal_surface;
using FaceTree =
    CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Mesh>>>;

/// Projection of remeshed vertices onto the original input surface.
struct ProjectOntoInput {
  const Mesh* mesh;
  const FaceTree* tree;
  Point operator()(Mesh::Vertex_index v) const { return tree->closest_point(mesh->point(v)); }
};

using EdgeFlags = Mesh::Property_map<Mesh::Edge_index, bool>;

int feature_degree(const Mesh& mesh, const EdgeFlags& flags, Mesh::Vertex_index v) {
  int count = 0;
  for (auto h : CGAL::halfedges_around_target(v, mesh)) count += flags[mesh.edge(h)] ? 1 : 0;
  return count;
}

/// Keeps only the flagged edges that form simple closed loops (every vertex of the
/// connected set of flagged edges has two flagged edges) at least `min_length` long:
/// rims of caps. Open or short creases (toes, skin folds) are unflagged.
void keep_closed_feature_loops(const Mesh& mesh, EdgeFlags& flags, double min_length) {
  std::vector<char> visited(mesh.num_edges(), 0);
  for (Mesh::Edge_index start : mesh.edges()) {
    if (!flags[start] || visited[start.idx()]) continue;
    std::vector<Mesh::Edge_index> component{start}, stack{start};
    visited[start.idx()] = 1;
    bool loop = true;
    double length = 0.0;
    while (!stack.empty()) {
      const Mesh::Edge_index e = stack.back();
      stack.pop_back();
      length += std::sqrt(
          CGAL::squared_distance(mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1))));
      for (int end = 0; end < 2; ++end) {
        const Mesh::Vertex_index v = mesh.vertex(e, end);
        if (feature_degree(mesh, flags, v) != 2) loop = false;
        for (auto h : CGAL::halfedges_around_target(v, mesh)) {
          const Mesh::Edge_index next = mesh.edge(h);
          if (flags[next] && !visited[next.idx()]) {
            visited[next.idx()] = 1;
            component.push_back(next);
            stack.push_back(next);
          }
        }
      }
    }
    if (!loop || length < min_length)
      for (Mesh::Edge_index e : component) flags[e] = false;
  }
}

/// Faces of intersecting pairs of `mesh` (garbage-free, so face i is Face_index(i)),
/// grown by `rings` rings of vertex-adjacent faces.
std::vector<Mesh::Face_index> intersecting_region(const Mesh& mesh, int rings) {
  std::vector<std::array<int, 2>> pairs;
  try {
    pairs = self_intersecting_face_pairs(from_cgal(mesh));
  } catch (const std::invalid_argument& e) {
    throw InputError("remesh", std::string("the remeshed surface is invalid: ") + e.what());
  }
  std::set<Mesh::Face_index> region;
  for (const auto& pair : pairs)
    for (int f : pair) region.insert(Mesh::Face_index(static_cast<Mesh::size_type>(f)));
  for (int ring = 0; ring < rings && !region.empty(); ++ring) {
    std::set<Mesh::Face_index> grown = region;
    for (Mesh::Face_index f : region)
      for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
        for (Mesh::Face_index g : CGAL::faces_around_target(mesh.halfedge(v), mesh))
          if (g != Mesh::null_face()) grown.insert(g);
    region.swap(grown);
  }
  return {region.begin(), region.end()};
}

}  // namespace

RemeshResult remesh_isotropic(const TriMesh& surface, const RemeshOptions& options) {
  if (!(options.edge_length > 0.0) || !std::isfinite(options.edge_length))
    throw InputError("remesh", "the edge length must be positive");
  if (options.iterations < 1) throw InputError("remesh", "at least one iteration is needed");
  Mesh mesh = to_cgal(surface, "remesh");
  if (!CGAL::is_closed(mesh)) throw InputError("remesh", "the surface is not closed");

  // Cap faces: all corners on one of the cap planes (up to round-off of the cut points).
  const double tolerance = 1e-9 * bbox_diagonal(mesh);
  auto is_cap = mesh.add_property_map<Mesh::Face_index, bool>("f:cap", false).first;
  for (Mesh::Face_index f : mesh.faces())
    for (const CropPlane& plane : options.cap_planes) {
      const Vec3 n = plane.normal.normalized();
      bool on_plane = true;
      for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
        const Point& p = mesh.point(v);
        on_plane =
            on_plane && std::abs(n.dot(Vec3(p.x(), p.y(), p.z()) - plane.point)) <= tolerance;
      }
      if (on_plane) is_cap[f] = true;
    }

  auto constrained = mesh.add_property_map<Mesh::Edge_index, bool>("e:constrained", false).first;
  if (options.sharp_angle_deg < 180.0) {
    PMP::detect_sharp_edges(mesh, options.sharp_angle_deg, constrained);
    keep_closed_feature_loops(mesh, constrained, options.min_feature_loop_length);
  }
  for (Mesh::Edge_index e : mesh.edges()) {
    const auto h = mesh.halfedge(e);
    if (is_cap[mesh.face(h)] != is_cap[mesh.face(mesh.opposite(h))]) constrained[e] = true;
  }
  // Vertices where feature lines meet or end are kept fixed.
  auto corner = mesh.add_property_map<Mesh::Vertex_index, bool>("v:corner", false).first;
  int feature_edges = 0;
  for (Mesh::Vertex_index v : mesh.vertices())
    corner[v] =
        feature_degree(mesh, constrained, v) % 2 == 1 || feature_degree(mesh, constrained, v) > 2;
  for (Mesh::Edge_index e : mesh.edges()) feature_edges += constrained[e] ? 1 : 0;

  const Mesh input = mesh;
  const auto params =
      CGAL::parameters::number_of_iterations(static_cast<unsigned int>(options.iterations))
          .edge_is_constrained_map(constrained)
          .vertex_is_constrained_map(corner)
          .protect_constraints(false);
  PMP::isotropic_remeshing(mesh.faces(), options.edge_length, mesh, params);
  mesh.collect_garbage();

  // Where parts of the input are closer than the edge length (lips, toes), the result can
  // intersect itself: remesh around the intersections with half the edge length, with
  // vertices projected onto the original input, up to `max_refinements` times.
  int rounds = 0;
  std::vector<Mesh::Face_index> region = intersecting_region(mesh, 2);
  if (!region.empty()) {
    FaceTree tree(CGAL::faces(input).first, CGAL::faces(input).second, input);
    tree.accelerate_distance_queries();
    for (; !region.empty() && rounds < options.max_refinements; ++rounds) {
      PMP::isotropic_remeshing(region, options.edge_length / std::pow(2.0, rounds + 1), mesh,
                               params.projection_functor(ProjectOntoInput{&mesh, &tree}));
      mesh.collect_garbage();
      region = intersecting_region(mesh, 2);
    }
  }
  if (!CGAL::is_closed(mesh)) throw InputError("remesh", "the remeshed surface is not closed");
  if (!region.empty())
    throw InputError("remesh",
                     "the surface remeshed at this edge length intersects itself (parts "
                     "of the body are closer than the edge length): use a smaller edge "
                     "length or crop that region");
  return {from_cgal(mesh), feature_edges, rounds};
}

}  // namespace tightfit
