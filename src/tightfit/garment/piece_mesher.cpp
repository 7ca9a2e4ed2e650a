#include "tightfit/garment/piece_mesher.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/lloyd_optimize_mesh_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace tightfit {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexInfo {
  int boundary = -1;  // index into the boundary polygon, −1 for interior vertices
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K, CGAL::Delaunay_mesh_vertex_base_2<K>>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_no_edge_refinement_2<Cdt, Criteria>;

double polygon_area(const Points2& p) {
  double a = 0.0;
  const Eigen::Index n = p.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    a += p(i, 0) * p(j, 1) - p(j, 0) * p(i, 1);
  }
  return 0.5 * a;
}

}  // namespace

PieceMesh mesh_piece(const Points2& boundary, double edge_length, int lloyd_iterations) {
  const int nb = static_cast<int>(boundary.rows());
  if (nb < 3) throw std::invalid_argument("mesh_piece: a boundary needs at least 3 vertices");
  if (!(edge_length > 0)) throw std::invalid_argument("mesh_piece: edge length must be positive");
  if (polygon_area(boundary) <= 0)
    throw std::invalid_argument("mesh_piece: the boundary is not counter-clockwise");

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles(nb);
  for (int i = 0; i < nb; ++i) {
    handles[i] = cdt.insert(K::Point_2(boundary(i, 0), boundary(i, 1)));
    if (handles[i]->info().boundary >= 0)
      throw std::invalid_argument("mesh_piece: two boundary vertices coincide");
    handles[i]->info().boundary = i;
  }
  try {
    for (int i = 0; i < nb; ++i) cdt.insert_constraint(handles[i], handles[(i + 1) % nb]);
  } catch (const std::exception&) {
    throw std::invalid_argument("mesh_piece: the boundary crosses itself");
  }
  if (static_cast<int>(cdt.number_of_vertices()) != nb)
    throw std::invalid_argument("mesh_piece: the boundary touches itself");

  Mesher mesher(cdt, Criteria(0.125, edge_length));
  mesher.init(false);  // no seeds: faces inside the polygon are the domain
  mesher.refine_mesh();
  if (lloyd_iterations > 0)
    CGAL::lloyd_optimize_mesh_2(cdt, CGAL::parameters::max_iteration_number = lloyd_iterations);

  // Collect the domain: boundary vertices first, then interior vertices in order of use.
  std::map<Cdt::Vertex_handle, int> index;
  for (int i = 0; i < nb; ++i) index[handles[i]] = i;
  std::vector<Vec2> interior;
  std::vector<std::array<int, 3>> tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    std::array<int, 3> t;
    for (int c = 0; c < 3; ++c) {
      const auto v = f->vertex(c);
      auto it = index.find(v);
      if (it == index.end()) {
        it = index.emplace(v, nb + static_cast<int>(interior.size())).first;
        interior.emplace_back(v->point().x(), v->point().y());
      }
      t[c] = it->second;
    }
    tris.push_back(t);
  }
  PieceMesh out;
  out.vertices.resize(nb + static_cast<Eigen::Index>(interior.size()), 2);
  out.vertices.topRows(nb) = boundary;
  for (size_t i = 0; i < interior.size(); ++i)
    out.vertices.row(nb + static_cast<Eigen::Index>(i)) = interior[i].transpose();
  out.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i)
    for (int c = 0; c < 3; ++c) out.triangles(static_cast<Eigen::Index>(i), c) = tris[i][c];
  return out;
}

double min_angle_deg(const Points2& x, const Triangles& t) {
  double best = t.rows() > 0 ? 180.0 : 0.0;
  for (Eigen::Index f = 0; f < t.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = x.row(t(f, (k + 1) % 3)) - x.row(t(f, k));
      const Vec2 b = x.row(t(f, (k + 2) % 3)) - x.row(t(f, k));
      const double ang = std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
      best = std::min(best, ang * 180.0 / 3.14159265358979323846);
    }
  return best;
}

}  // namespace tightfit
