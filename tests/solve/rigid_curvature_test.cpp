/// Analytic pressure checks on rigid bodies whose curvature varies:
/// a sleeve on a truncated cone (radius varying along the axis) and on an elliptic
/// cylinder (curvature varying around it). Laplace's law with the local principal
/// curvatures gives the pressure, p = tr(T Λ) = κ_hoop τᵀ T τ (the meridian / axial
/// curvature is zero on both), with T the simulated membrane tension and Λ the EXACT
/// shape operator of the analytic surface at the element. The simulated pressure (mid-edge
/// and limit-surface operators) must agree within 1 % on irregular garment meshes, away
/// from the pinned end rings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "rigid_body_case.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/body/loop_limit.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::rigid_curvature_test {

using test::rigid_body;
using test::rigid_materials;

/// The exact shape operator of the analytic surface near a point: Λ = κ τ τᵀ, τ the unit
/// direction of the curved principal direction (the other principal curvature is 0).
struct CurvedDirection {
  double curvature = 0.0;  ///< 1/m
  Vec3 direction = Vec3::UnitX();
};

struct CurvedBodyCase {
  const char* name;
  Body body;
  std::unique_ptr<LimitSurface> surface;
  SleeveParams sleeve;
  std::function<CurvedDirection(const Vec3&)> exact;
};

CylinderParams base_cylinder() {
  CylinderParams c;
  c.radius = 0.05;
  c.length = 0.3;
  c.edge_length = 0.004;
  return c;
}

SleeveParams base_sleeve(double radius, double hoop_scale) {
  SleeveParams s;
  s.radius = radius;
  s.axial_begin = -0.06;
  s.axial_end = 0.06;
  s.hoop_scale = hoop_scale;
  s.axial_scale = 0.95;
  s.edge_length = 0.006;
  s.jitter = 0.3;
  s.pin_first_ring = s.pin_last_ring = true;
  return s;
}

/// Elliptic cylinder x²/a² + y²/b² = 1 (capped): the circular capsule mapped by the
/// affine map diag(a/R, b/R, 1). Loop subdivision commutes with affine maps, so the
/// limit surface of the mapped control mesh is the mapped limit surface, whose vertices
/// lie on the analytic capsule: the side is an exact elliptic cylinder at the vertices.
CurvedBodyCase elliptic_case(double a, double b) {
  CurvedBodyCase c{"elliptic cylinder", {}, nullptr, {}, {}};
  const CylinderParams cyl = base_cylinder();
  TriMesh mesh = cylinder_surface(cyl);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices(v, 0) *= a / cyl.radius;
    mesh.vertices(v, 1) *= b / cyl.radius;
  }
  c.body = rigid_body(std::move(mesh));
  c.surface = std::make_unique<LimitSurface>(c.body.surface);
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  const double perimeter = M_PI * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
  c.sleeve = base_sleeve(perimeter / (2 * M_PI), 0.9);
  c.exact = [a, b](const Vec3& p) {
    const double t = std::atan2(p.y() / b, p.x() / a);  // ellipse parameter of p
    const double s = std::sin(t), co = std::cos(t);
    const double speed = std::sqrt(a * a * s * s + b * b * co * co);
    return CurvedDirection{a * b / (speed * speed * speed), Vec3(-a * s, b * co, 0.0) / speed};
  };
  return c;
}

/// Truncated cone of radius R (1 + k z) (capped): the circular capsule mapped by
/// Φ(x, y, z) = ((1 + k z) x, (1 + k z) y, z), its limit surface fitted to Φ(capsule)
/// with the projection Φ ∘ project_to_cylinder ∘ Φ⁻¹ (onto the surface, along the
/// radius at fixed z).
CurvedBodyCase cone_case(double k) {
  CurvedBodyCase c{"cone", {}, nullptr, {}, {}};
  CylinderParams cyl = base_cylinder();
  cyl.fit_limit = false;
  TriMesh mesh = cylinder_surface(cyl);
  auto scale = [k](double z) { return 1.0 + k * z; };
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const double s = scale(mesh.vertices(v, 2));
    mesh.vertices(v, 0) *= s;
    mesh.vertices(v, 1) *= s;
  }
  const CylinderParams fitted = base_cylinder();
  const LimitFitResult fit = fit_loop_limit(mesh, [&](const Vec3& p) {
    const double s = scale(p.z());
    const Vec3 q = project_to_cylinder(fitted, Vec3(p.x() / s, p.y() / s, p.z()));
    const double sq = scale(q.z());
    return Vec3(sq * q.x(), sq * q.y(), q.z());
  });
  EXPECT_LT(fit.max_residual, 1e-9);
  c.body = rigid_body(std::move(mesh));
  c.surface = std::make_unique<LimitSurface>(c.body.surface);
  // Rest circumference 0.8 of the middle one: hoop stretch 1.14 .. 1.36 along the sleeve.
  c.sleeve = base_sleeve(cyl.radius, 0.8);
  const double R = cyl.radius;
  c.exact = [k, R](const Vec3& p) {
    const double r = R * (1 + k * p.z());
    const double cos_half_angle = 1.0 / std::sqrt(1.0 + (k * R) * (k * R));
    const Vec3 hoop = Vec3(-p.y(), p.x(), 0.0).normalized();
    return CurvedDirection{cos_half_angle / r, hoop};
  };
  return c;
}

struct Errors {
  double max = 0.0, rms = 0.0;
  int checked = 0;
};

struct LaplaceCheck {
  Errors mid_edge, limit_surface;
  double pressure_ratio = 0.0;  ///< largest / smallest Laplace pressure checked
};

/// Simulates the sleeve of `c` and compares both simulated pressures with Laplace's law.
LaplaceCheck check_laplace_law(CurvedBodyCase c) {
  Garment g = make_sleeve(c.sleeve, *c.surface, c.body.surface.vertices);
  GarmentSimulation sim(c.body, *c.surface, std::move(g), rigid_materials());
  EXPECT_TRUE(sim.solve().converged);
  const FitAnalysis fit = sim.analyze();
  const Points3& x = sim.garment_positions();
  const Triangles& tri = sim.garment().topology->garment_triangles;
  // Away from the pinned rings: every corner at least 1.5 cm from the sleeve's ends.
  const double margin = 0.015;
  Errors mid, limit;
  double p_min = 1e300, p_max = 0.0;
  for (Eigen::Index e = 0; e < tri.rows(); ++e) {
    Vec3 centroid = Vec3::Zero();
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = x.row(tri(e, k)).transpose();
      centroid += p / 3.0;
      inside &= p.z() > c.sleeve.axial_begin + margin && p.z() < c.sleeve.axial_end - margin;
    }
    if (!inside) continue;
    const CurvedDirection d = c.exact(centroid);
    const Vec3 n = fit.elements[e].normal;
    const Vec3 tau = (d.direction - d.direction.dot(n) * n).normalized();
    const double expected = d.curvature * tau.dot(fit.elements[e].tension * tau);
    EXPECT_GT(expected, 0.0);
    p_min = std::min(p_min, expected);
    p_max = std::max(p_max, expected);
    for (auto [errors, value] :
         {std::pair{&mid, fit.pressure_mid_edge[e]}, std::pair{&limit, fit.pressure_limit[e]}}) {
      const double r = std::abs(value / expected - 1.0);
      errors->max = std::max(errors->max, r);
      errors->rms += r * r;
      ++errors->checked;
    }
  }
  for (Errors* errors : {&mid, &limit}) errors->rms = std::sqrt(errors->rms / errors->checked);
  std::printf(
      "%s: %d of %d elements checked, Laplace pressure %.1f .. %.1f Pa; error "
      "max/rms mid-edge %.3f/%.3f %%, limit surface %.3f/%.3f %%\n",
      c.name, mid.checked, static_cast<int>(tri.rows()), p_min, p_max, 100 * mid.max, 100 * mid.rms,
      100 * limit.max, 100 * limit.rms);
  EXPECT_GT(mid.checked, tri.rows() / 2);
  return {mid, limit, p_max / p_min};
}

TEST(RigidCurvedBody, ConePressureFollowsTheLocalHoopCurvature) {
  // Radius 5 cm ± 9 % over the sleeve's 12 cm (half-angle 4.3°).
  const LaplaceCheck check = check_laplace_law(cone_case(1.5));
  EXPECT_GT(check.pressure_ratio, 1.3);  // the pressure really varies along the sleeve
  EXPECT_LT(check.limit_surface.max, 0.01);
  EXPECT_LT(check.mid_edge.max, 0.01);
}

// Semi-axes 6 and 4 cm: curvature 11 .. 37.5 /m around the body. The limit-surface
// operator meets Laplace's law within 1 %. The paper's mid-edge operator (Eq. 32-33)
// does not: minimizing Σ A tr(Λ²) over the edge unknowns smooths the curvature where it
// varies, a FIRST-order error in the edge length (measured: 9 % at 6 mm, 4.4 % at 3 mm,
// with or without jitter; exact on the cylinder and the sphere, where κ is constant).
// The test pins that behaviour down: the error halves with the edge length.
TEST(RigidCurvedBody, EllipticCylinderPressureFollowsTheLocalCurvature) {
  CurvedBodyCase coarse = elliptic_case(0.06, 0.04);
  const LaplaceCheck at_6mm = check_laplace_law(std::move(coarse));
  EXPECT_GT(at_6mm.pressure_ratio, 3.0);
  EXPECT_LT(at_6mm.limit_surface.max, 0.01);
  CurvedBodyCase fine = elliptic_case(0.06, 0.04);
  fine.sleeve.edge_length = 0.003;
  const LaplaceCheck at_3mm = check_laplace_law(std::move(fine));
  EXPECT_LT(at_3mm.limit_surface.max, 0.01);
  EXPECT_LT(at_6mm.mid_edge.max, 0.12);
  EXPECT_LT(at_3mm.mid_edge.max, 0.6 * at_6mm.mid_edge.max);
  EXPECT_LT(at_3mm.mid_edge.rms, 0.6 * at_6mm.mid_edge.rms);
}

}  // namespace tightfit::rigid_curvature_test
