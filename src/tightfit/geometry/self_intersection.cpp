/// The only translation unit of the geometry layer that includes CGAL (compile time).
#include "tightfit/geometry/self_intersection.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

namespace tightfit {

std::vector<std::array<int, 2>> self_intersecting_face_pairs(const TriMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  using Face = Mesh::Face_index;

  Mesh sm;
  std::vector<Mesh::Vertex_index> vertices;
  vertices.reserve(static_cast<std::size_t>(mesh.num_vertices()));
  for (int i = 0; i < mesh.num_vertices(); ++i)
    vertices.push_back(sm.add_vertex(
        Kernel::Point_3(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2))));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Face face = sm.add_face(vertices[mesh.faces(f, 0)], vertices[mesh.faces(f, 1)],
                                  vertices[mesh.faces(f, 2)]);
    if (face == Mesh::null_face() || static_cast<int>(face.idx()) != f)
      throw std::invalid_argument("self_intersecting_face_pairs: face " + std::to_string(f) +
                                  " does not fit a manifold, consistently oriented mesh");
  }
  std::vector<std::pair<Face, Face>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  std::vector<std::array<int, 2>> out;
  out.reserve(pairs.size());
  for (const auto& [a, b] : pairs) {
    const int fa = static_cast<int>(a.idx());
    const int fb = static_cast<int>(b.idx());
    out.push_back({std::min(fa, fb), std::max(fa, fb)});
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tightfit
