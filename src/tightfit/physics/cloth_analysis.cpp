#include "tightfit/physics/cloth_analysis.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/physics/element_pressure.hpp"

namespace tightfit {

std::vector<ClothElementFit> analyze_cloth(const ClothEnergy& cloth, const VecX& x) {
  if (x.size() != 3 * static_cast<Eigen::Index>(cloth.num_garment_vertices()))
    throw std::invalid_argument("analyze_cloth: position vector has wrong size");
  const Triangles tri = cloth.garment_triangles();
  const double t = cloth.material().thickness;
  std::vector<ClothElementFit> out(cloth.num_triangles());
  for (int e = 0; e < cloth.num_triangles(); ++e) {
    ClothElementFit& fit = out[e];
    const Mat32 F = cloth.deformation_gradient(x, e);
    const Mat2 C = F.transpose() * F;
    const Vec2 ev = symmetric_eigenvalues(C).cwiseMax(0.0);
    fit.stretch = ev.cwiseSqrt();
    fit.grain_stretch = Vec2(std::sqrt(C(0, 0)), std::sqrt(C(1, 1)));
    fit.regime = cloth.law().regime(C);
    fit.rest_area = cloth.rest_area(e);
    const Vec3 a = x.segment<3>(3 * tri(e, 0));
    const Vec3 n = (x.segment<3>(3 * tri(e, 1)) - a).cross(x.segment<3>(3 * tri(e, 2)) - a);
    const double J = fit.stretch[0] * fit.stretch[1];
    fit.deformed_area = J * fit.rest_area;
    if (!(n.norm() > 0.0) || !(J > 1e-12)) continue;  // degenerate: no frame, no stress
    fit.normal = n.normalized();
    const Vec3 d1 = F * symmetric_major_eigenvector(C);
    fit.direction1 = d1.normalized();
    fit.direction2 = fit.normal.cross(fit.direction1);
    const std::optional<Mat3> sigma = cauchy_stress<double>(cloth.law(), F);
    if (!sigma) continue;
    fit.cauchy_stress = *sigma;
    fit.tension = t * fit.cauchy_stress;
    Eigen::Matrix<double, 3, 2> frame;
    frame << fit.direction1, fit.direction2;
    fit.principal_tension = symmetric_eigenvalues(frame.transpose() * fit.tension * frame);
  }
  return out;
}

VecX young_laplace_pressure(const std::vector<ClothElementFit>& fit,
                            const std::vector<Mat3>& shape_operators) {
  if (fit.size() != shape_operators.size())
    throw std::invalid_argument("young_laplace_pressure: " + std::to_string(fit.size()) +
                                " elements but " + std::to_string(shape_operators.size()) +
                                " shape operators");
  VecX p(static_cast<Eigen::Index>(fit.size()));
  for (std::size_t e = 0; e < fit.size(); ++e)
    p[static_cast<Eigen::Index>(e)] =
        young_laplace_pressure<double>(fit[e].tension, shape_operators[e]);
  return p;
}

VecX mixed_voronoi_areas(const Points3& vertices, const Triangles& faces) {
  VecX area = VecX::Zero(vertices.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<Vec3, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = vertices.row(faces(f, k)).transpose();
    const double a = triangle_area(p[0], p[1], p[2]);
    if (!(a > 0.0)) continue;
    // cot of the angle at corner k, and whether that angle is obtuse.
    std::array<double, 3> cot{};
    int obtuse = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = p[(k + 1) % 3] - p[k];
      const Vec3 v = p[(k + 2) % 3] - p[k];
      const double dot = u.dot(v);
      cot[k] = dot / u.cross(v).norm();
      if (dot < 0.0) obtuse = k;
    }
    for (int k = 0; k < 3; ++k) {
      double share;
      if (obtuse < 0) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        share = ((p[i] - p[k]).squaredNorm() * cot[j] + (p[j] - p[k]).squaredNorm() * cot[i]) / 8.0;
      } else {
        share = (k == obtuse) ? a / 2.0 : a / 4.0;
      }
      area[faces(f, k)] += share;
    }
  }
  return area;
}

Points3 vertex_normals(const Points3& vertices, const Triangles& faces) {
  Points3 n = Points3::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vec3 a = vertices.row(faces(f, 0)).transpose();
    const Vec3 c = (vertices.row(faces(f, 1)).transpose() - a)
                       .cross(vertices.row(faces(f, 2)).transpose() - a);
    for (int k = 0; k < 3; ++k) n.row(faces(f, k)) += c.transpose();
  }
  for (Eigen::Index i = 0; i < n.rows(); ++i) {
    const double len = n.row(i).norm();
    if (len > 0.0) n.row(i) /= len;
  }
  return n;
}

VecX vertex_area_pressure(const Points3& vertices, const Triangles& faces, const VecX& gradient) {
  if (gradient.size() != 3 * vertices.rows())
    throw std::invalid_argument("vertex_area_pressure: gradient has wrong size");
  const VecX area = mixed_voronoi_areas(vertices, faces);
  const Points3 normal = vertex_normals(vertices, faces);
  VecX p = VecX::Zero(vertices.rows());
  for (Eigen::Index i = 0; i < vertices.rows(); ++i)
    if (area[i] > 0.0) p[i] = gradient.segment<3>(3 * i).dot(normal.row(i).transpose()) / area[i];
  return p;
}

}  // namespace tightfit
