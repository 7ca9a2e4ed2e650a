#include "tightfit/body/crop_and_cap.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>

#include "tightfit/body/cgal_surface_mesh.hpp"
#include "tightfit/body/local_crop.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using namespace cgal_surface;

}  // namespace

TriMesh crop_and_cap(const TriMesh& surface, const std::vector<CropPlane>& planes) {
  Mesh mesh = to_cgal(surface, "crop");
  for (size_t i = 0; i < planes.size(); ++i) {
    const std::string source = "crop plane " + std::to_string(i);
    if (planes[i].local) {
      mesh = to_cgal(crop_beyond_nearest_loop(from_cgal(mesh), planes[i], source), source);
      continue;
    }
    const Vec3& n = planes[i].normal;
    if (!(n.norm() > 0.0) || !n.allFinite() || !planes[i].point.allFinite())
      throw InputError(source, "the normal must be a non-zero finite vector");
    // Vertices (almost) on the plane would leave near-duplicate cut points and needle
    // faces: push them off it by ε = 1e-7 of the size of the mesh, keeping their side
    // (vertices exactly on it go to the kept side).
    const Vec3 unit = n.normalized();
    const double epsilon = 1e-7 * bbox_diagonal(mesh);
    for (Mesh::Vertex_index v : mesh.vertices()) {
      const Point& p = mesh.point(v);
      const Vec3 x(p.x(), p.y(), p.z());
      const double d = unit.dot(x - planes[i].point);
      if (std::abs(d) < epsilon) {
        const Vec3 moved = x + ((d < 0.0 ? -epsilon : epsilon) - d) * unit;
        mesh.point(v) = Point(moved.x(), moved.y(), moved.z());
      }
    }
    // CGAL keeps the negative side of its plane: flip the normal to keep the side it points to.
    const Kernel::Plane_3 plane(
        Point(planes[i].point.x(), planes[i].point.y(), planes[i].point.z()),
        Kernel::Vector_3(-n.x(), -n.y(), -n.z()));
    bool manifold = false;
    try {
      manifold = PMP::clip(mesh, plane,
                           CGAL::parameters::clip_volume(true).throw_on_self_intersection(true));
    } catch (const PMP::Corefinement::Self_intersection_exception&) {
      throw InputError(source, "the surface intersects itself near the cut");
    }
    if (!manifold) throw InputError(source, "the cut could not be closed into a manifold surface");
    if (mesh.number_of_faces() == 0)
      throw InputError(source, "the plane removes the whole surface");
    // Cuts through vertices or along edges leave zero-area faces: collapse them.
    if (!PMP::remove_degenerate_faces(mesh))
      throw InputError(source, "the cut left degenerate faces that could not be removed");
    mesh.collect_garbage();
    if (!CGAL::is_closed(mesh)) throw InputError(source, "the cut surface is not closed");
  }
  return from_cgal(mesh);
}

}  // namespace tightfit
