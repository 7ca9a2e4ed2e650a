#include "tightfit/physics/cloth_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "physics_test_util.hpp"
#include "support/energy_assembly.hpp"
#include "test_surfaces.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit::test::cloth_analysis_test {

/// A sleeve: the cylinder mesh's pattern unrolled and shrunk by (s_hoop, s_axial), so
/// that wrapping it on the cylinder stretches it by about (s_hoop, s_axial).
struct Sleeve {
  CylinderMesh mesh;
  std::shared_ptr<const Points2> rest;  ///< the rest array the cloth reads
  ClothEnergy cloth;
  VecX x;
};

Sleeve make_sleeve(double R, double s_hoop, double s_axial, double jitter, bool diagonals, int n) {
  CylinderMesh m = cylinder_mesh(R, 0.1, 2 * M_PI, n, n / 3, jitter, diagonals, 5);
  auto rest = std::make_shared<Points2>(m.param.rows(), 2);
  for (int p = 0; p < m.param.rows(); ++p)
    rest->row(p) << R * m.param(p, 0) / s_hoop, m.param(p, 1) / s_axial;
  ClothEnergy cloth(m.pattern_faces, *rest, m.to_garment, static_cast<int>(m.garment.rows()));
  const VecX x = flatten(m.garment);
  return {std::move(m), std::move(rest), std::move(cloth), x};
}

/// StVK hoop tension (N/m) of a membrane stretched by (s1, s2) along its principal axes.
double stvk_tension(const ClothMaterial& m, double s1, double s2) {
  const double e1 = (s1 * s1 - 1) / 2, e2 = (s2 * s2 - 1) / 2;
  const double S1 = m.lame_lambda() * (e1 + e2) + 2 * m.lame_mu() * e1;
  return m.thickness * s1 * S1 / s2;  // t σ11, σ = F S Fᵀ / J
}

TEST(ClothAnalysis, StretchesDirectionsAndStressOfAUniformlyStretchedSleeve) {
  const double R = 0.05, s1 = 1.2, s2 = 1.05;
  const Sleeve sl = make_sleeve(R, s1, s2, 0.0, false, 64);
  const auto fit = analyze_cloth(sl.cloth, sl.x);
  ASSERT_EQ(static_cast<int>(fit.size()), sl.cloth.num_triangles());
  const double chord = std::sin(M_PI / 64) / (M_PI / 64);  // chord/arc on this mesh
  const double T = stvk_tension(sl.cloth.material(), s1 * chord, s2);
  const Triangles faces = sl.cloth.garment_triangles();
  for (int e = 0; e < static_cast<int>(fit.size()); ++e) {
    const ClothElementFit& f = fit[e];
    Vec3 centroid = Vec3::Zero();
    for (int k = 0; k < 3; ++k) centroid += sl.mesh.garment.row(faces(e, k)).transpose() / 3;
    EXPECT_GT(f.normal.dot(Vec3(centroid.x(), centroid.y(), 0).normalized()), 0.99);  // outward
    EXPECT_NEAR(f.stretch[0], s1 * chord, 1e-9);
    EXPECT_NEAR(f.stretch[1], s2, 1e-9);
    EXPECT_EQ(f.regime, ClothRegime::kTaut);
    EXPECT_NEAR(std::abs(f.direction1.z()), 0.0, 1e-9);  // hoop
    EXPECT_NEAR(std::abs(f.direction2.z()), 1.0, 1e-9);  // axial
    EXPECT_NEAR(f.direction1.dot(f.normal), 0.0, 1e-12);
    EXPECT_NEAR(f.principal_tension[0] / T, 1.0, 1e-9);
    EXPECT_NEAR(f.direction1.dot(f.tension * f.direction1) / T, 1.0, 1e-9);
    EXPECT_NEAR((f.tension * f.normal).norm(), 0.0, 1e-9 * T);
    EXPECT_NEAR(f.deformed_area / f.rest_area, s1 * chord * s2, 1e-9);
    EXPECT_LT((f.tension - sl.cloth.material().thickness * f.cauchy_stress).norm(), 1e-12 * T);
  }
}

TEST(ClothAnalysis, WrinkledElementCarriesOnlyUniaxialTension) {
  // Hoop stretch 1.2 with the axial direction compressed to 0.8: wrinkled, no axial tension.
  const Sleeve sl = make_sleeve(0.05, 1.2, 0.8, 0.0, false, 64);
  for (const ClothElementFit& f : analyze_cloth(sl.cloth, sl.x)) {
    EXPECT_EQ(f.regime, ClothRegime::kWrinkled);
    EXPECT_LT(std::abs(f.principal_tension[1]), 1e-3 * f.principal_tension[0]);
  }
  // Compressed both ways: slack, no tension at all.
  const Sleeve slack = make_sleeve(0.05, 0.9, 0.9, 0.0, false, 64);
  for (const ClothElementFit& f : analyze_cloth(slack.cloth, slack.x)) {
    EXPECT_EQ(f.regime, ClothRegime::kSlack);
    EXPECT_EQ(f.tension.norm(), 0.0);
  }
}

struct PressureErrors {
  double max = 0.0, rms = 0.0;
};

PressureErrors errors(const VecX& p, double exact, const std::vector<bool>& use) {
  PressureErrors e;
  int n = 0;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    if (!use[i]) continue;
    const double r = p[i] / exact - 1.0;
    e.max = std::max(e.max, std::abs(r));
    e.rms += r * r;
    ++n;
  }
  e.rms = std::sqrt(e.rms / std::max(n, 1));
  return e;
}

TEST(ClothAnalysis, SleevePressureIsHoopTensionOverRadius) {
  const double R = 0.05, s1 = 1.2, s2 = 1.05;
  for (bool irregular : {false, true}) {
    const Sleeve sl = make_sleeve(R, s1, s2, irregular ? 0.2 : 0.0, irregular, 64);
    const auto fit = analyze_cloth(sl.cloth, sl.x);
    const double T = stvk_tension(sl.cloth.material(), s1, s2);  // continuum
    const double exact = T / R;

    // Young-Laplace with the mid-edge shape operator on the garment mesh.
    const VecX p_mid = young_laplace_pressure(
        fit, mid_edge_shape_operators(sl.mesh.garment, sl.mesh.garment_faces));
    // ... with the exact shape operator of the cylinder (θ̂ θ̂ᵀ / R at the element).
    std::vector<Mat3> exact_shape(fit.size());
    for (std::size_t e = 0; e < fit.size(); ++e) {
      const Vec3 hoop = Vec3::UnitZ().cross(fit[e].normal).normalized();
      exact_shape[e] = hoop * hoop.transpose() / R;
    }
    const VecX p_exact_op = young_laplace_pressure(fit, exact_shape);
    // Vertex force over mixed Voronoi area.
    const VecX p_vertex = vertex_area_pressure(sl.mesh.garment, sl.mesh.garment_faces,
                                               test::energy_gradient(sl.cloth, sl.x));

    const std::vector<bool> all_faces(fit.size(), true);
    std::vector<bool> interior_vertices(sl.mesh.garment.rows());
    for (std::size_t v = 0; v < interior_vertices.size(); ++v)
      interior_vertices[v] = !sl.mesh.boundary_garment[v];
    const PressureErrors em = errors(p_mid, exact, all_faces);
    const PressureErrors ex = errors(p_exact_op, exact, all_faces);
    const PressureErrors ev = errors(p_vertex, exact, interior_vertices);
    const double operator_only = (p_mid.array() / p_exact_op.array() - 1).abs().maxCoeff();
    std::cout << "[" << (irregular ? "irregular" : "regular") << " sleeve 64x21, p = " << exact
              << " Pa] relative error max/rms: mid-edge " << em.max << "/" << em.rms
              << ", exact operator " << ex.max << "/" << ex.rms << ", vertex area " << ev.max << "/"
              << ev.rms << "; mid-edge vs exact operator (same tension) " << operator_only << "\n";
    EXPECT_LT(em.max, 0.01);
    EXPECT_LT(ex.max, 0.01);
    if (!irregular) {
      EXPECT_LT(ev.max, 0.01);
    }
    EXPECT_GT(p_mid.minCoeff(), 0.0);  // fabric presses onto the convex body
  }
}

TEST(ClothAnalysis, SpherePressureIsTwiceTensionOverRadius) {
  const double R = 0.1, T0 = 50.0;  // isotropic tension (N/m)
  Points3 v;
  Triangles f;
  icosphere(R, 4, v, f);
  std::vector<ClothElementFit> fit(f.rows());
  std::vector<Mat3> exact_shape(f.rows());
  for (int e = 0; e < f.rows(); ++e) {
    const Vec3 a = v.row(f(e, 0)).transpose();
    fit[e].normal =
        (v.row(f(e, 1)).transpose() - a).cross(v.row(f(e, 2)).transpose() - a).normalized();
    fit[e].tension = T0 * (Mat3::Identity() - fit[e].normal * fit[e].normal.transpose());
    exact_shape[e] = fit[e].tension / (T0 * R);
  }
  const VecX p = young_laplace_pressure(fit, mid_edge_shape_operators(v, f));
  const double exact = 2 * T0 / R;
  EXPECT_LT((p.array() / exact - 1).abs().maxCoeff(), 2e-3);
  EXPECT_LT((young_laplace_pressure(fit, exact_shape).array() / exact - 1).abs().maxCoeff(), 1e-12);
  // Faces oriented inwards: the same fabric would lift off a concave surface.
  Triangles flipped = f;
  flipped.col(1).swap(flipped.col(2));
  const VecX q = young_laplace_pressure(fit, mid_edge_shape_operators(v, flipped));
  EXPECT_LT(q.maxCoeff(), 0.0);
}

TEST(ClothAnalysis, VoronoiAreasTileTheSurface) {
  Points3 v;
  Triangles f;
  icosphere(1.0, 2, v, f);
  double total = 0.0;
  for (int e = 0; e < f.rows(); ++e)
    total += 0.5 * (v.row(f(e, 1)) - v.row(f(e, 0))).cross(v.row(f(e, 2)) - v.row(f(e, 0))).norm();
  EXPECT_NEAR(mixed_voronoi_areas(v, f).sum(), total, 1e-12 * total);
  const Points3 n = vertex_normals(v, f);
  for (int i = 0; i < v.rows(); ++i) EXPECT_GT(n.row(i).dot(v.row(i)), 0.99);
}

}  // namespace tightfit::test::cloth_analysis_test
