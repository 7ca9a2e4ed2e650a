#include "tightfit/body/cgal_surface_mesh.hpp"

#include <cmath>
#include <vector>

#include <CGAL/Polygon_mesh_processing/bbox.h>

#include "tightfit/common/error.hpp"

namespace tightfit::cgal_surface {

Mesh to_cgal(const TriMesh& m, const std::string& source) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v(static_cast<size_t>(m.num_vertices()));
  for (int i = 0; i < m.num_vertices(); ++i)
    v[i] = mesh.add_vertex(Point(m.vertices(i, 0), m.vertices(i, 1), m.vertices(i, 2)));
  for (int f = 0; f < m.num_faces(); ++f)
    if (mesh.add_face(v[m.faces(f, 0)], v[m.faces(f, 1)], v[m.faces(f, 2)]) == Mesh::null_face())
      throw InputError(source, "face " + std::to_string(f) +
                                   " makes the surface non-manifold or inconsistently oriented");
  return mesh;
}

TriMesh from_cgal(const Mesh& mesh) {
  TriMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  std::vector<int> index(mesh.num_vertices(), -1);
  int next = 0;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    m.vertices.row(next) << p.x(), p.y(), p.z();
    index[v.idx()] = next++;
  }
  m.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  int f = 0;
  for (Mesh::Face_index face : mesh.faces()) {
    int c = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(face), mesh))
      m.faces(f, c++) = index[v.idx()];
    ++f;
  }
  return m;
}

double bbox_diagonal(const Mesh& mesh) {
  const CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(mesh);
  return std::sqrt(std::pow(b.xmax() - b.xmin(), 2) + std::pow(b.ymax() - b.ymin(), 2) +
                   std::pow(b.zmax() - b.zmin(), 2));
}

}  // namespace tightfit::cgal_surface
