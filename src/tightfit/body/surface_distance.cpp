// CGAL AABB tree for point-surface distances (the only body TU with CGAL's AABB tree).
#include "tightfit/body/surface_distance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

namespace tightfit {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct SurfaceDistance::Impl {
  std::vector<Triangle> triangles;
  TriMesh mesh;
  Tree tree;
};

SurfaceDistance::SurfaceDistance(const TriMesh& surface) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = surface;
  impl_->triangles.reserve(static_cast<size_t>(surface.num_faces()));
  auto point = [&](int v) {
    return Point(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  };
  for (int f = 0; f < surface.num_faces(); ++f)
    impl_->triangles.emplace_back(point(surface.faces(f, 0)), point(surface.faces(f, 1)),
                                  point(surface.faces(f, 2)));
  impl_->tree.rebuild(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

double SurfaceDistance::distance(const Vec3& p) const {
  return std::sqrt(impl_->tree.squared_distance(Point(p.x(), p.y(), p.z())));
}

Vec3 SurfaceDistance::closest_point(const Vec3& p) const {
  const Point q = impl_->tree.closest_point(Point(p.x(), p.y(), p.z()));
  return {q.x(), q.y(), q.z()};
}

int SurfaceDistance::closest_face(const Vec3& p, Vec3* point) const {
  const auto [q, id] = impl_->tree.closest_point_and_primitive(Point(p.x(), p.y(), p.z()));
  if (point) *point = {q.x(), q.y(), q.z()};
  return static_cast<int>(id - impl_->triangles.cbegin());
}

double SurfaceDistance::winding_number(const Vec3& p) const {
  // Solid angle of each triangle seen from p (Van Oosterom & Strackee 1983).
  const TriMesh& m = impl_->mesh;
  double total = 0.0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 a = m.vertices.row(m.faces(f, 0)).transpose() - p;
    const Vec3 b = m.vertices.row(m.faces(f, 1)).transpose() - p;
    const Vec3 c = m.vertices.row(m.faces(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

}  // namespace tightfit
