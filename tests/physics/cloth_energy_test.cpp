#include "tightfit/physics/cloth_energy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>

#include "physics_test_util.hpp"
#include "support/energy_assembly.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit::test::cloth_energy_test {

/// One pattern triangle (random shape, unit size) deformed with principal stretches
/// (s1, s2) along a random in-plane direction, then rotated and moved in 3D.
struct Triangle {
  Points2 rest;
  VecX x;
};

Triangle stretched_triangle(double s1, double s2, unsigned seed) {
  std::mt19937 rng(seed);
  Triangle t;
  t.rest.resize(3, 2);
  t.rest << 0.0, 0.0, uniform(rng, 0.8, 1.2), uniform(rng, -0.2, 0.2), uniform(rng, 0.1, 0.6),
      uniform(rng, 0.7, 1.1);
  const double a = uniform(rng, 0.0, 3.14159);
  Mat2 v;
  v << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  Mat32 f = Mat32::Zero();
  f(0, 0) = s1;
  f(1, 1) = s2;
  f = random_rotation(seed + 100) * f * v.transpose();
  const Vec3 shift(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  t.x.resize(9);
  for (int k = 0; k < 3; ++k) t.x.segment<3>(3 * k) = f * t.rest.row(k).transpose() + shift;
  return t;
}

ClothEnergy single(const Triangle& t, ClothMaterial m = {}) {
  Triangles tri(1, 3);
  tri << 0, 1, 2;
  return ClothEnergy(tri, t.rest, {0, 1, 2}, 3, m);
}

double stretch_for_strain(double e) { return std::sqrt(1.0 + 2.0 * e); }

struct FdErrors {
  double gradient, hessian, rest_gradient, mixed;
};

FdErrors fd_errors(const ClothEnergy& energy_in, const VecX& x, double h) {
  ClothEnergy energy = energy_in;
  FdErrors r{};
  const VecX g = test::energy_gradient(energy, x);
  r.gradient =
      check_gradient([&](const VecX& y) { return energy.value(y); }, g, x, h).relative_error;
  const MatX H = MatX(test::energy_hessian(energy, x));
  r.hessian =
      check_hessian([&](const VecX& y) { return test::energy_gradient(energy, y); }, H, x, h)
          .relative_error;
  const Points2 rest0 = energy.rest();
  const VecX xbar = flatten(rest0);
  Points2 trial = rest0;
  auto set = [&](const VecX& v) {
    trial = Eigen::Map<const Points2>(v.data(), rest0.rows(), 2);
    energy.bind_rest(trial);
  };
  VecX gr = VecX::Zero(xbar.size());
  energy.add_gradient_rest(x, gr);
  r.rest_gradient = check_gradient(
                        [&](const VecX& v) {
                          set(v);
                          const double u = energy.value(x);
                          set(xbar);
                          return u;
                        },
                        gr, xbar, h)
                        .relative_error;
  std::vector<Triplet> t;
  energy.add_mixed_rest(x, t);
  const MatX mixed = MatX(test::sparse_from_triplets(x.size(), xbar.size(), t));
  r.mixed = check_jacobian(
                [&](const VecX& v) {
                  set(v);
                  const VecX gx = test::energy_gradient(energy, x);
                  set(xbar);
                  return gx;
                },
                mixed, xbar, h)
                .relative_error;
  return r;
}

void expect_fd_ok(const ClothEnergy& energy, const VecX& x, const std::string& what) {
  const FdErrors e = fd_errors(energy, x, 1e-6);
  EXPECT_LT(e.gradient, 1e-6) << what;
  EXPECT_LT(e.hessian, 1e-6) << what;
  EXPECT_LT(e.rest_gradient, 1e-6) << what;
  EXPECT_LT(e.mixed, 1e-6) << what;
}

TEST(ClothEnergy, WrinkledEnergyIsPaperEq10) {
  // W_StVK(λ1, λ̄2(λ1)) = μ(λ+μ)/(2(λ+2μ)) (λ1-1)², and with plane-stress constants E/8 (λ1-1)².
  ClothMaterial m;
  m.regime_smoothing = 1e-7;
  const RelaxedStVK law(m);
  const double la = m.lame_lambda(), mu = m.lame_mu();
  for (double l1 : {1.05, 1.3, 1.69}) {
    const double l2bar = law.wrinkle_threshold(l1);
    const double stvk = la / 8 * std::pow(l1 + l2bar - 2, 2) +
                        mu / 4 * (std::pow(l1 - 1, 2) + std::pow(l2bar - 1, 2));
    const double closed = mu * (la + mu) / (2 * (la + 2 * mu)) * std::pow(l1 - 1, 2);
    EXPECT_NEAR(stvk / closed, 1.0, 1e-12);
    EXPECT_NEAR(closed / (m.youngs_modulus / 8 * std::pow(l1 - 1, 2)), 1.0, 1e-12);
    for (double l2 : {0.5 * l2bar, 0.9 * l2bar}) {
      // Wrinkled: the density does not depend on λ2.
      EXPECT_NEAR(law.density(l1 + l2, l1 * l2) / closed, 1.0, 1e-6) << l1 << " " << l2;
      Mat2 c = Mat2::Zero();
      c(0, 0) = l1;
      c(1, 1) = l2;
      EXPECT_EQ(law.regime(c), ClothRegime::kWrinkled);
    }
  }
}

TEST(ClothEnergy, SlackClothHasZeroEnergyAndForce) {
  for (auto [s1, s2] : {std::pair{0.95, 0.95}, std::pair{0.99, 0.5}, std::pair{0.9, 0.8}}) {
    const Triangle t = stretched_triangle(s1, s2, 4);
    const ClothEnergy e = single(t);
    EXPECT_EQ(e.value(t.x), 0.0);
    EXPECT_EQ(test::energy_gradient(e, t.x).norm(), 0.0);
    EXPECT_EQ(MatX(test::energy_hessian(e, t.x)).norm(), 0.0);
    Mat2 c = Mat2::Zero();
    c(0, 0) = s1 * s1;
    c(1, 1) = s2 * s2;
    EXPECT_EQ(e.law().regime(c), ClothRegime::kSlack);
  }
}

TEST(ClothEnergy, BiaxialStressIsStVK) {
  ClothMaterial m;
  const RelaxedStVK law(m);
  const double la = m.lame_lambda(), mu = m.lame_mu();
  for (auto [s1, s2] : {std::pair{1.3, 1.1}, std::pair{1.2, 1.2}, std::pair{1.3, 0.99}}) {
    Mat2 c;
    c << s1 * s1, 0.0, 0.0, s2 * s2;
    const Mat2 rot = Eigen::Rotation2Dd(0.4).toRotationMatrix();
    c = rot * c * rot.transpose();
    const Mat2 strain = 0.5 * (c - Mat2::Identity());
    const Mat2 expected = la * strain.trace() * Mat2::Identity() + 2 * mu * strain;
    EXPECT_EQ(law.regime(c), ClothRegime::kTaut);
    EXPECT_LT((law.second_piola(c) - expected).norm(), 1e-9 * expected.norm()) << s1 << " " << s2;
    // Energy = t A (W_StVK + const).
    const Triangle t = stretched_triangle(s1, s2, 9);
    const ClothEnergy e = single(t, m);
    const double w = la / 2 * std::pow(strain.trace(), 2) + mu * (strain * strain).trace();
    const double k1 = m.youngs_modulus, k2 = la + 2 * mu, nu = m.poisson_ratio;
    const double delta = m.regime_smoothing, eps = delta / 2;
    const double offset =
        (k1 + k2) * delta * delta / 6 + (k1 + k2 * (1 - nu) * (1 - nu)) * eps * eps / 2;
    EXPECT_NEAR(e.value(t.x) / (m.thickness * e.rest_area(0) * (w + offset)), 1.0, 1e-12);
  }
}

TEST(ClothEnergy, UniaxialStressHasNoLateralComponent) {
  // Stretched along one axis with the lateral direction free to contract (wrinkled):
  // S1 = E e1, S2 = 0 (up to the smoothing, O(δ²/(e1-e2))).
  ClothMaterial m;
  const RelaxedStVK law(m);
  for (double s1 : {1.1, 1.3}) {
    const double e1 = 0.5 * (s1 * s1 - 1);
    Mat2 c = Mat2::Zero();
    c(0, 0) = s1 * s1;
    c(1, 1) = 0.6;
    ASSERT_EQ(law.regime(c), ClothRegime::kWrinkled);
    const Mat2 s = law.second_piola(c);
    EXPECT_NEAR(s(0, 0) / (m.youngs_modulus * e1), 1.0, 1e-4);
    EXPECT_LT(std::abs(s(1, 1)), 1e-4 * s(0, 0));
    EXPECT_EQ(s(0, 1), 0.0);
  }
}

TEST(ClothEnergy, DerivativesMatchFiniteDifferencesInEveryRegime) {
  for (double delta : {1e-3, 2e-2}) {
    ClothMaterial m;
    m.regime_smoothing = delta;
    const RelaxedStVK law(m);
    const double nu = m.poisson_ratio;  // ν' for plane stress
    struct Case {
      double e1, e2;
      const char* what;
    };
    std::vector<Case> cases = {
        {0.3, 0.1, "taut"},
        {0.3, -0.2, "wrinkled"},
        {-0.05, -0.1, "slack"},
        {0.5 * delta, -0.1, "slack/wrinkled band, inside"},
        {-0.5 * delta, -0.1, "slack/wrinkled band, slack side"},
        {1.5 * delta, -0.1, "slack/wrinkled, just beyond the band"},
        {0.2, -nu * 0.2 + 0.5 * delta, "wrinkled/taut band, taut side"},
        {0.2, -nu * 0.2 - 0.5 * delta, "wrinkled/taut band, wrinkled side"},
        {0.2, -nu * 0.2 - 1.5 * delta, "wrinkled/taut, just beyond the band"},
        {0.15, 0.15 - 1e-7, "taut, lambda1 ~ lambda2"},
        {0.15, 0.15, "taut, lambda1 = lambda2"},
        {0.3 * delta, 0.2 * delta, "rest corner, lambda1 ~ lambda2 ~ 1"},
        {0.0, 0.0, "rest state"},
        {-0.3 * delta, -0.3 * delta - 1e-8, "slack side of the rest corner"},
    };
    unsigned seed = 20;
    for (const Case& c : cases) {
      const Triangle t =
          stretched_triangle(stretch_for_strain(c.e1), stretch_for_strain(c.e2), ++seed);
      const ClothEnergy e = single(t, m);
      ASSERT_TRUE(std::isfinite(e.value(t.x))) << c.what;
      if (c.e1 == 0.0 && c.e2 == 0.0) {
        EXPECT_TRUE(test::energy_gradient(e, t.x).allFinite());
        EXPECT_TRUE(MatX(test::energy_hessian(e, t.x)).allFinite());
      }
      expect_fd_ok(e, t.x, std::string(c.what) + " delta=" + std::to_string(delta));
    }
  }
}

/// The smoothing variables of relaxed_stvk.hpp (plane stress: ν' = ν, ε = δ/2).
Vec2 smoothing_variables(double e1, double e2, const ClothMaterial& m) {
  const double nu = m.poisson_ratio, eps = m.regime_smoothing / 2;
  const double mean = (e1 + e2) / 2, r = std::hypot((e1 - e2) / 2, eps);
  return Vec2(mean + r, (1 + nu) * mean - (1 - nu) * r);
}

/// e1 (with e2 fixed) at which smoothing variable `which` equals `target`, by bisection.
double strain_at(int which, double target, double e2, double lo, double hi,
                 const ClothMaterial& m) {
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (smoothing_variables(mid, e2, m)[which] < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ClothEnergy, SecondDerivativeIsContinuousAcrossBandEdges) {
  ClothMaterial m;
  m.regime_smoothing = 1e-2;
  const double d = m.regime_smoothing;
  // Both edges z = ±δ of the slack/wrinkled band (z1, e2 = -0.1) and of the
  // wrinkled/taut band (z2, e2 = -0.05).
  struct Edge {
    int which;
    double z, e2, lo, hi;
  };
  for (const Edge& edge : {Edge{0, -d, -0.1, -0.1, 0.1}, Edge{0, d, -0.1, -0.1, 0.1},
                           Edge{1, -d, -0.05, 0.0, 0.5}, Edge{1, d, -0.05, 0.0, 0.5}}) {
    const double e1 = strain_at(edge.which, edge.z, edge.e2, edge.lo, edge.hi, m);
    const Triangle a =
        stretched_triangle(stretch_for_strain(e1 - 1e-9), stretch_for_strain(edge.e2), 3);
    const Triangle b =
        stretched_triangle(stretch_for_strain(e1 + 1e-9), stretch_for_strain(edge.e2), 3);
    const ClothEnergy ea = single(a, m);
    const MatX ha = MatX(test::energy_hessian(ea, a.x));
    const MatX hb = MatX(test::energy_hessian(single(b, m), b.x));
    // A jump in the second derivative would be of the order of the stiffness E t A.
    const double scale = m.youngs_modulus * m.thickness * ea.rest_area(0);
    EXPECT_LT((ha - hb).norm(), 1e-6 * scale) << edge.which << " " << edge.z;
  }
}

TEST(ClothEnergy, ConvergesToEq10AsSmoothingVanishes) {
  const Triangle t = stretched_triangle(1.2, 0.9, 5);  // wrinkled
  const ClothMaterial base;
  const double l1 = 1.44;
  const double exact_density = base.youngs_modulus / 8 * std::pow(l1 - 1, 2);
  double previous = 1.0;
  for (double delta : {1e-2, 1e-3, 1e-4}) {
    ClothMaterial m = base;
    m.regime_smoothing = delta;
    const ClothEnergy e = single(t, m);
    const double err = std::abs(e.value(t.x) / (m.thickness * e.rest_area(0)) / exact_density - 1);
    EXPECT_LT(err, previous);
    previous = err;
  }
  EXPECT_LT(previous, 1e-6);
}

TEST(ClothEnergy, WeldedPiecesDerivativesMatchFiniteDifferences) {
  // Two pattern pieces (2 triangles each) sewn along one edge: pattern vertices 1,2 and
  // 4,5 meet at garment vertices 1,2.
  Points2 rest(8, 2);
  rest << 0, 0, 1, 0, 1, 1, 0, 1,  // piece A: square 0-1-2-3
      0, 0, 1.1, 0, 1.1, 1, 0, 1;  // piece B: square 4-5-6-7 (slightly wider)
  Triangles tri(4, 3);
  tri << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  const std::vector<int> to_garment = {0, 1, 2, 3, 1, 4, 5, 2};
  ClothMaterial m;
  m.regime_smoothing = 1e-2;
  const ClothEnergy e(tri, rest, to_garment, 6, m);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Points3 x(6, 3);
    x << 0, 0, 0, 1.2, 0, 0, 1.2, 1.1, 0, 0, 1.1, 0.1, 2.4, 0.1, 0.2, 2.4, 1.0, 0.3;
    VecX xv = flatten(x) + 0.1 * random_vector(18, seed);
    expect_fd_ok(e, xv, "welded, seed " + std::to_string(seed));
  }
  const Triangles g = e.garment_triangles();
  EXPECT_EQ(g(2, 0), 1);
  EXPECT_EQ(g(3, 1), 5);
}

TEST(ClothEnergy, ElementHessiansSumToTheHessian) {
  // Two pieces welded along an edge (as above): shared garment vertices get blocks from
  // triangles of both pieces.
  Points2 rest(8, 2);
  rest << 0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 1.1, 0, 1.1, 1, 0, 1;
  Triangles tri(4, 3);
  tri << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  const ClothEnergy e(tri, rest, {0, 1, 2, 3, 1, 4, 5, 2}, 6);
  Points3 x(6, 3);
  x << 0, 0, 0, 0.9, 0, 0, 1.2, 1.1, 0, 0, 1.1, 0.1, 2.4, 0.1, 0.2, 2.4, 1.0, 0.3;
  const VecX xv = flatten(x) + 0.05 * random_vector(18, 4);
  for (const bool project : {false, true}) {
    const MatX H = MatX(test::energy_hessian(e, xv, project));
    const MatX sum = test::element_hessian_sum(e, xv, project);
    ASSERT_EQ(sum.rows(), 18);
    EXPECT_LT((sum - H).norm(), 1e-13 * H.norm());
  }
}

TEST(ClothEnergy, ProjectedHessianIsPositiveSemiDefinite) {
  const Triangle t = stretched_triangle(1.2, 0.8, 17);  // wrinkled: indefinite raw Hessian
  const ClothEnergy e = single(t);
  Eigen::SelfAdjointEigenSolver<MatX> raw(MatX(test::energy_hessian(e, t.x)));
  Eigen::SelfAdjointEigenSolver<MatX> projected(MatX(test::energy_hessian(e, t.x, true)));
  EXPECT_LT(raw.eigenvalues().minCoeff(), 0.0);
  EXPECT_GT(projected.eigenvalues().minCoeff(), -1e-9 * projected.eigenvalues().maxCoeff());
}

// A taut element's Hessian is a sum of PSD terms (the metric Hessian and the tensile
// stress): the projection leaves it exactly as it is (no eigen-decomposition round-off).
TEST(ClothEnergy, ATautElementsHessianIsNotProjected) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const Triangle t = stretched_triangle(1.25, 1.1, seed);
    const ClothEnergy e = single(t);
    const MatX raw = MatX(test::energy_hessian(e, t.x));
    const MatX projected = MatX(test::energy_hessian(e, t.x, true));
    EXPECT_EQ(raw, projected) << "seed " << seed;
    Eigen::SelfAdjointEigenSolver<MatX> eig(raw);
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * eig.eigenvalues().maxCoeff());
  }
}

TEST(ClothEnergy, RejectsBadInput) {
  Points2 rest(3, 2);
  rest << 0, 0, 1, 0, 2, 0;  // collinear
  Triangles tri(1, 3);
  tri << 0, 1, 2;
  EXPECT_THROW(ClothEnergy(tri, rest, {0, 1, 2}, 3), InputError);
  rest(2, 1) = 1.0;
  EXPECT_THROW(ClothEnergy(tri, rest, {0, 1, 3}, 3), InputError);
  EXPECT_THROW(ClothEnergy(tri, rest, {0, 1}, 3), InputError);
  ClothMaterial m;
  m.regime_smoothing = 0.0;
  EXPECT_THROW(ClothEnergy(tri, rest, {0, 1, 2}, 3, m), InputError);
  ClothEnergy ok(tri, rest, {0, 1, 2}, 3);
  Points2 flat = rest;
  flat(2, 1) = 0.0;
  EXPECT_THROW(ok.bind_rest(flat), InputError);
}

/// A measured knit with a soft toe and a stiff rise, wale about twice the course.
ClothMaterial measured_knit(double coupling) {
  auto fabric = std::make_shared<MeasuredFabric>(
      MeasuredFabric{"test knit", FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 40.0, 130.0, 420.0}),
                     FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 25.0, 80.0, 260.0}), std::nullopt,
                     std::nullopt, coupling, 30.0});
  ClothMaterial m;
  m.thickness = 5e-4;
  m.measured = fabric;
  return m;
}

TEST(ClothEnergy, MeasuredFabricDerivativesMatchFiniteDifferences) {
  for (double coupling : {0.0, 0.4}) {
    const ClothMaterial m = measured_knit(coupling);
    // Taut both ways, stretched one way (the other slack), slack, near the toe, one
    // direction inside the compression ramp (where the shear fades) with the other
    // slack or stretched.
    for (auto [s1, s2] : {std::pair{1.3, 1.15}, std::pair{1.4, 0.9}, std::pair{0.95, 0.9},
                          std::pair{1.0005, 1.0002}, std::pair{2.1, 1.6}, std::pair{0.9996, 0.95},
                          std::pair{1.25, 0.9997}}) {
      for (unsigned seed : {1u, 2u, 3u}) {
        const Triangle t = stretched_triangle(s1, s2, seed);
        expect_fd_ok(single(t, m), t.x,
                     "measured c=" + std::to_string(coupling) + " s=" + std::to_string(s1) + "," +
                         std::to_string(s2) + " seed " + std::to_string(seed));
      }
    }
  }
}

TEST(ClothEnergy, MeasuredStripCarriesTheMeasuredTension) {
  // A rest rectangle W × H (two triangles) stretched by λ along one material direction,
  // unchanged across: with coupling 0 the force per unit rest width, (dU/dλ)/(W H), is
  // the strip curve T(λ − 1) of that direction.
  const ClothMaterial m = measured_knit(0.0);
  const MeasuredFabric& f = *m.measured;
  const double w = 0.03, h = 0.05;
  Points2 rest(4, 2);
  rest << 0, 0, w, 0, w, h, 0, h;
  Triangles tri(2, 3);
  tri << 0, 1, 2, 0, 2, 3;
  const ClothEnergy energy(tri, rest, {0, 1, 2, 3}, 4, m);
  for (int axis : {0, 1}) {
    const FabricCurve& curve = axis == 0 ? f.course : f.wale;
    for (double strain : {0.05, 0.2, 0.35, 0.7, 1.0, 1.3}) {
      auto u = [&](double lambda) {
        VecX x(12);
        for (int k = 0; k < 4; ++k) {
          Vec2 p = rest.row(k).transpose();
          p[axis] *= lambda;
          x.segment<3>(3 * k) = Vec3(p.x(), p.y(), 0.0);
        }
        return energy.value(x);
      };
      const double l = 1.0 + strain, step = 1e-6;
      const double tension = (u(l + step) - u(l - step)) / (2 * step) / (w * h);
      EXPECT_NEAR(tension / curve.tension(strain), 1.0, 5e-3) << axis << " " << strain;
    }
  }
}

TEST(FabricCurve, InterpolatesMonotonicallyAndExtrapolatesWithTheLastSlope) {
  const FabricCurve c({0.0, 0.1, 0.3, 0.6}, {0.0, 5.0, 40.0, 200.0}, 1e-3);
  for (std::size_t k = 1; k < c.strains().size(); ++k)
    EXPECT_NEAR(c.tension(c.strains()[k]), c.tensions()[k], 1e-9);
  double previous = 0.0;
  for (double e = 0.0; e < 0.9; e += 0.001) {
    const FabricCurve::Evaluation v = c.evaluate(e);
    EXPECT_GE(v.tension, previous - 1e-12);
    EXPECT_GE(v.stiffness, -1e-9);
    previous = v.tension;
    const double step = 1e-7;
    EXPECT_NEAR((c.evaluate(e + step).energy - c.evaluate(e - step).energy) / (2 * step), v.tension,
                1e-5 * (1.0 + v.tension));
    EXPECT_NEAR((c.tension(e + step) - c.tension(e - step)) / (2 * step), v.stiffness,
                1e-4 * (1.0 + v.stiffness));
  }
  EXPECT_NEAR(c.tension(0.8) - c.tension(0.7), 0.1 * (200.0 - 40.0) / 0.3, 1e-9);
  EXPECT_EQ(c.evaluate(-0.01).energy, 0.0);
  EXPECT_EQ(c.evaluate(-0.01).tension, 0.0);
  // A curve given from a first strain above 0 starts at (0, 0).
  EXPECT_EQ(FabricCurve({0.1, 0.2}, {3.0, 9.0}).strains().size(), 3u);
}

TEST(FabricCurve, RefusesCurvesThatAreNoStripTest) {
  EXPECT_THROW(FabricCurve({0.0, 0.2, 0.1}, {0.0, 1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({0.0, 0.1, 0.2}, {0.0, 2.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({-0.1, 0.2}, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({0.0, 0.2}, {0.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({0.0}, {0.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({0.0, 0.1}, {0.0, 1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(FabricCurve({0.0, 0.1}, {1.0, 2.0}), std::invalid_argument);
}

TEST(FabricLaw, MeasuredStressMatchesTheEnergyAndCouplingMustBeBelowOne) {
  const ClothMaterial m = measured_knit(0.3);
  const FabricLaw law(m);
  Mat2 c;
  c << 1.3, 0.08, 0.08, 1.6;
  const Mat2 s = law.second_piola(c);
  const double step = 1e-7;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      Mat2 cp = c, cm = c;
      cp(a, b) += step;
      cm(a, b) -= step;
      if (a != b) {
        cp(b, a) += step;
        cm(b, a) -= step;
      }
      const double dw = (law.evaluate(strain_components(cp), 0).value -
                         law.evaluate(strain_components(cm), 0).value) /
                        (2 * step);
      EXPECT_NEAR(a == b ? 2.0 * dw : dw, s(a, b), 1e-4 * s.norm()) << a << b;
    }
  ClothMaterial bad = measured_knit(1.0);
  EXPECT_THROW(FabricLaw{bad}, InputError);
}

}  // namespace tightfit::test::cloth_energy_test
