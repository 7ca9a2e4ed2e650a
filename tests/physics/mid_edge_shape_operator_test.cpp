#include "tightfit/physics/mid_edge_shape_operator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "test_surfaces.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::test::mid_edge_shape_operator_test {

/// Eigenvalues of Λ in the face's tangent plane, and the eigenvalue along `axis`.
struct Curvatures {
  double mean;    // (k1 + k2)/2
  double along;   // aᵀ Λ a for the unit tangent direction closest to `axis`
  double across;  // bᵀ Λ b, b = n × a
  double normal;  // |Λ n|
  double asymmetry;
};

Curvatures curvatures(const Mat3& L, const Points3& v, const Triangles& f, int face,
                      const Vec3& axis) {
  const Vec3 p0 = v.row(f(face, 0)).transpose();
  const Vec3 n =
      (v.row(f(face, 1)).transpose() - p0).cross(v.row(f(face, 2)).transpose() - p0).normalized();
  const Vec3 a = (axis - axis.dot(n) * n).normalized();
  const Vec3 b = n.cross(a);
  return {0.5 * L.trace(), a.dot(L * a), b.dot(L * b), (L * n).norm(), (L - L.transpose()).norm()};
}

TEST(MidEdgeShapeOperator, SphereHasUmbilicCurvatureOneOverR) {
  const double R = 0.1;
  for (double jitter : {0.0, 0.2}) {
    Points3 v;
    Triangles f;
    icosphere(R, 4, v, f, jitter, 3);  // 5120 faces, valence 5 and 6
    const std::vector<Mat3> L = mid_edge_shape_operators(v, f);
    double max_err = 0.0, sum_err = 0.0, max_aniso = 0.0;
    for (int e = 0; e < f.rows(); ++e) {
      const Curvatures c = curvatures(L[e], v, f, e, Vec3(0.3, 0.5, 0.8).normalized());
      EXPECT_LT(c.normal, 1e-9 / R);
      max_err = std::max(max_err, std::abs(c.mean * R - 1.0));
      sum_err += std::abs(c.mean * R - 1.0);
      max_aniso = std::max(max_aniso, std::abs(c.along - c.across) * R);
    }
    std::cout << "[sphere, 5120 faces, jitter " << jitter << "] mean-curvature error: max "
              << max_err << ", mean " << sum_err / f.rows() << "; max |k_a - k_b| R " << max_aniso
              << "\n";
    EXPECT_LT(max_err, 0.01);
    EXPECT_LT(max_aniso, 0.05);
  }
}

struct CylinderStats {
  double max_mean_err = 0, max_axial = 0, max_hoop_err = 0;  // interior faces
  double max_mean_err_boundary = 0, max_hoop_err_boundary = 0, max_axial_boundary = 0;
};

CylinderStats cylinder_stats(const CylinderMesh& m, double R) {
  const std::vector<Mat3> L = mid_edge_shape_operators(m.garment, m.garment_faces);
  CylinderStats s;
  for (int e = 0; e < m.garment_faces.rows(); ++e) {
    const Curvatures c = curvatures(L[e], m.garment, m.garment_faces, e, Vec3::UnitZ());
    EXPECT_LT(c.asymmetry, 1e-9 / R);
    bool on_boundary = false;
    for (int k = 0; k < 3; ++k) on_boundary |= m.boundary_garment[m.garment_faces(e, k)];
    const double mean_err = std::abs(c.mean * 2 * R - 1.0);  // mean curvature 1/(2R)
    const double hoop_err = std::abs(c.across * R - 1.0);
    const double axial = std::abs(c.along) * R;
    if (on_boundary) {
      s.max_mean_err_boundary = std::max(s.max_mean_err_boundary, mean_err);
      s.max_hoop_err_boundary = std::max(s.max_hoop_err_boundary, hoop_err);
      s.max_axial_boundary = std::max(s.max_axial_boundary, axial);
    } else {
      s.max_mean_err = std::max(s.max_mean_err, mean_err);
      s.max_hoop_err = std::max(s.max_hoop_err, hoop_err);
      s.max_axial = std::max(s.max_axial, axial);
    }
  }
  return s;
}

void print(const char* what, const CylinderStats& s) {
  std::cout << "[" << what << "] interior: max |H 2R - 1| " << s.max_mean_err
            << ", max |k_hoop R - 1| " << s.max_hoop_err << ", max |k_axial| R " << s.max_axial
            << "; boundary faces: " << s.max_mean_err_boundary << ", " << s.max_hoop_err_boundary
            << ", " << s.max_axial_boundary << "\n";
}

TEST(MidEdgeShapeOperator, RegularCylinderHasHoopCurvatureOneOverRAndNoneAlongTheAxis) {
  const double R = 0.05;
  const CylinderMesh m = cylinder_mesh(R, 0.1, 2 * M_PI, 64, 20, 0.0, false, 1);
  const CylinderStats s = cylinder_stats(m, R);
  print("regular cylinder 64x20", s);
  EXPECT_LT(s.max_hoop_err, 2e-3);
  EXPECT_LT(s.max_axial, 1e-3);
  EXPECT_LT(s.max_hoop_err_boundary, 2e-3);
  EXPECT_LT(s.max_axial_boundary, 1e-3);
}

TEST(MidEdgeShapeOperator, IrregularCylinder) {
  // Interior nodes jittered by up to 20 % of the spacing, quads split along random
  // diagonals (valences 4 to 8).
  const double R = 0.05;
  const CylinderMesh m = cylinder_mesh(R, 0.1, 2 * M_PI, 64, 20, 0.2, true, 7);
  const CylinderStats s = cylinder_stats(m, R);
  print("irregular cylinder 64x20", s);
  EXPECT_LT(s.max_hoop_err, 2e-3);
  EXPECT_LT(s.max_axial, 2e-3);
  EXPECT_LT(s.max_hoop_err_boundary, 2e-3);
  EXPECT_LT(s.max_axial_boundary, 2e-3);
}

TEST(MidEdgeShapeOperator, ErrorConvergesQuadraticallyOnIrregularMeshes) {
  const double R = 0.05;
  double previous = 0.0;
  for (int n : {32, 64, 128}) {
    const CylinderMesh m = cylinder_mesh(R, 0.1, 2 * M_PI, n, n / 4, 0.2, true, 11);
    const double err = cylinder_stats(m, R).max_hoop_err;
    if (previous > 0.0) {
      EXPECT_LT(err, 0.35 * previous) << n;
    }
    previous = err;
  }
}

TEST(MidEdgeShapeOperator, CurvatureAcrossAnOpenBoundaryIsLostOnlyNearIt) {
  // Half cylinder cut along the axis: boundary edges run along the axis, the surface
  // curves across them. Documented behaviour: t_iᵀ Λ t_i = 0 in the boundary faces, and
  // the error decays about tenfold per ring of faces.
  const double R = 0.05;
  const int n = 32;
  const CylinderMesh m = cylinder_mesh(R, 0.1, M_PI, n, 20, 0.0, false, 1);
  const std::vector<Mat3> L = mid_edge_shape_operators(m.garment, m.garment_faces);
  std::vector<double> worst(n, 0.0);
  for (int e = 0; e < m.garment_faces.rows(); ++e) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 3; ++k) c += m.garment.row(m.garment_faces(e, k)).transpose() / 3;
    const double th = std::atan2(c.y(), c.x());
    const int ring = static_cast<int>(std::min(th, M_PI - th) / (M_PI / n));
    const Curvatures k = curvatures(L[e], m.garment, m.garment_faces, e, Vec3::UnitZ());
    worst[ring] = std::max(worst[ring], std::abs(k.across * R - 1.0));
  }
  std::cout << "[half cylinder 32x20] max hoop-curvature error by ring from the cut:";
  for (int r = 0; r < 5; ++r) std::cout << " " << worst[r];
  std::cout << "\n";
  EXPECT_NEAR(worst[0], 1.0, 1e-9);
  EXPECT_LT(worst[1], 0.2);
  EXPECT_LT(worst[2], 0.02);
  for (int r = 4; r < n / 2; ++r) EXPECT_LT(worst[r], 1e-3) << r;
}

TEST(MidEdgeShapeOperator, FlatMeshHasZeroCurvature) {
  const CylinderMesh m = cylinder_mesh(1.0, 1.0, 1.0, 8, 8, 0.3, true, 3);
  Points3 flat(m.garment.rows(), 3);
  for (int p = 0; p < m.param.rows(); ++p)
    flat.row(m.to_garment[p]) << m.param(p, 0), m.param(p, 1), 0.0;
  for (const Mat3& L : mid_edge_shape_operators(flat, m.garment_faces)) EXPECT_LT(L.norm(), 1e-12);
}

TEST(MidEdgeShapeOperator, RejectsBadTopology) {
  Triangles f(2, 3);
  f << 0, 1, 2, 0, 1, 3;  // both faces run 0 → 1
  EXPECT_THROW(MidEdgeShapeOperator(f, 4), InputError);
  f << 0, 1, 2, 1, 0, 4;
  EXPECT_THROW(MidEdgeShapeOperator(f, 4), InputError);
  Triangles nm(3, 3);
  nm << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  EXPECT_THROW(MidEdgeShapeOperator(nm, 5), InputError);
}

}  // namespace tightfit::test::mid_edge_shape_operator_test
