#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "physics_test_util.hpp"
#include "support/energy_assembly.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/physics/assembly.hpp"
#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/pin_energy.hpp"
#include "tightfit/physics/seam_spring_energy.hpp"
#include "tightfit/physics/sum_energy.hpp"

namespace tightfit::test::seam_pin_sum_test {

/// Two seam sides: pattern vertices 0-1-2 (piece A) and 3-4-5 (piece B, longer) are
/// welded pairwise into garment vertices 0, 1, 2; pattern vertex 6 is garment vertex 3.
struct SeamSetup {
  Points2 rest;
  std::vector<int> to_garment = {0, 1, 2, 0, 1, 2, 3};
  std::vector<std::array<int, 2>> edges;
  SeamMaterial material{0.005, 2e-4, 5.4e6};
  SeamSetup() {
    rest.resize(7, 2);
    rest << 0, 0, 0.1, 0, 0.2, 0.01, 1, 1, 1, 1.12, 1.01, 1.25, 2, 2;
    edges = polyline_edges({{0, 1, 2}, {3, 4, 5}});
  }
};

TEST(SeamSpringEnergy, PolylineEdgesAreConsecutivePairs) {
  const auto e = polyline_edges({{0, 1, 2}, {7}, {3, 4}});
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[1], (std::array<int, 2>{1, 2}));
  EXPECT_EQ(e[2], (std::array<int, 2>{3, 4}));
}

TEST(SeamSpringEnergy, EnergyOfEachSideUsesItsOwnRestLength) {
  SeamSetup s;
  const SeamSpringEnergy seams(s.edges, s.rest, s.to_garment, 4, s.material);
  Points3 x(4, 3);
  x << 0, 0, 0, 0.11, 0, 0, 0.22, 0, 0, 5, 5, 5;
  const double ka = 0.005 * 2e-4 * 5.4e6;
  EXPECT_DOUBLE_EQ(seams.axial_stiffness(), ka);
  double expected = 0.0;
  for (auto [a, b] : s.edges) {
    const double l0 = (s.rest.row(b) - s.rest.row(a)).norm();
    const double l = (x.row(s.to_garment[b]) - x.row(s.to_garment[a])).norm();
    expected += 0.5 * ka / l0 * (l - l0) * (l - l0);
  }
  EXPECT_NEAR(seams.value(flatten(x)), expected, 1e-15);
  // At each side's rest length alone the spring is unloaded.
  SeamSpringEnergy side_a(polyline_edges({{0, 1}}), s.rest, s.to_garment, 4, s.material);
  x.row(1) << 0.1, 0, 0;
  EXPECT_EQ(side_a.value(flatten(x)), 0.0);
  EXPECT_EQ(test::energy_gradient(side_a, flatten(x)).norm(), 0.0);
}

TEST(SeamSpringEnergy, DerivativesMatchFiniteDifferences) {
  SeamSetup s;
  SeamSpringEnergy seams(s.edges, s.rest, s.to_garment, 4, s.material);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const VecX x = 0.2 * random_vector(12, seed);
    const VecX g = test::energy_gradient(seams, x);
    EXPECT_LT(
        check_gradient([&](const VecX& y) { return seams.value(y); }, g, x, 1e-6).relative_error,
        1e-6);
    EXPECT_LT(check_hessian([&](const VecX& y) { return test::energy_gradient(seams, y); },
                            MatX(test::energy_hessian(seams, x)), x, 1e-6)
                  .relative_error,
              1e-6);
    const VecX xbar = flatten(s.rest);
    Points2 trial = s.rest;
    auto with_rest = [&](const VecX& v, auto fn) {
      trial = Eigen::Map<const Points2>(v.data(), 7, 2);
      seams.bind_rest(trial);
      auto r = fn();
      seams.bind_rest(s.rest);
      return r;
    };
    VecX gr = VecX::Zero(14);
    seams.add_gradient_rest(x, gr);
    EXPECT_LT(
        check_gradient([&](const VecX& v) { return with_rest(v, [&] { return seams.value(x); }); },
                       gr, xbar, 1e-6)
            .relative_error,
        1e-6);
    std::vector<Triplet> t;
    seams.add_mixed_rest(x, t);
    EXPECT_LT(check_jacobian(
                  [&](const VecX& v) {
                    return with_rest(v, [&] { return test::energy_gradient(seams, x); });
                  },
                  MatX(test::sparse_from_triplets(12, 14, t)), xbar, 1e-6)
                  .relative_error,
              1e-6);
  }
}

TEST(SeamSpringEnergy, RejectsBadInput) {
  SeamSetup s;
  EXPECT_THROW(SeamSpringEnergy(s.edges, s.rest, s.to_garment, 3, s.material), InputError);
  EXPECT_THROW(SeamSpringEnergy({{0, 9}}, s.rest, s.to_garment, 4, s.material), InputError);
  EXPECT_THROW(SeamSpringEnergy(s.edges, s.rest, s.to_garment, 4, SeamMaterial{0, 1, 1}),
               InputError);
  Points2 bad = s.rest;
  bad.row(1) = bad.row(0);
  EXPECT_THROW(SeamSpringEnergy(s.edges, bad, s.to_garment, 4, s.material), InputError);
}

TEST(PinEnergy, ValueAndDerivatives) {
  Points3 targets(2, 3);
  targets << 1, 2, 3, -1, 0, 0.5;
  const PinEnergy pins({2, 0}, targets, 1e3);
  const VecX x = random_vector(9, 4);
  const double expected = 0.5e3 * ((x.segment<3>(6) - targets.row(0).transpose()).squaredNorm() +
                                   (x.segment<3>(0) - targets.row(1).transpose()).squaredNorm());
  EXPECT_NEAR(pins.value(x), expected, 1e-12);
  const VecX g = test::energy_gradient(pins, x);
  EXPECT_LT(check_gradient([&](const VecX& y) { return pins.value(y); }, g, x, 1e-4).relative_error,
            1e-9);
  EXPECT_LT(check_hessian([&](const VecX& y) { return test::energy_gradient(pins, y); },
                          MatX(test::energy_hessian(pins, x)), x, 1e-4)
                .relative_error,
            1e-9);
  EXPECT_THROW(PinEnergy({0}, targets, 1.0), InputError);
  EXPECT_THROW(PinEnergy({0, 1}, targets, 0.0), InputError);
  EXPECT_THROW(pins.value(VecX::Zero(6)), std::invalid_argument);
}

TEST(SumEnergy, WeightedSumOfTerms) {
  SeamSetup s;
  auto seams = std::make_shared<SeamSpringEnergy>(s.edges, s.rest, s.to_garment, 4, s.material);
  Triangles tri(1, 3);
  tri << 0, 1, 6;
  auto cloth = std::make_shared<ClothEnergy>(tri, s.rest, s.to_garment, 4);
  Points3 targets(1, 3);
  targets << 0.3, 0.3, 0.3;
  auto pins = std::make_shared<PinEnergy>(std::vector<int>{3}, targets, 50.0);
  SumEnergy sum;
  sum.add(seams);
  sum.add(cloth, 2.0);
  sum.add(pins, 0.5);
  EXPECT_EQ(sum.num_terms(), 3);
  Points3 xp(4, 3);
  xp << 0, 0, 0, 0.12, 0, 0, 0.25, 0.01, 0, 2.1, 2.3, 0.1;
  const VecX x = flatten(xp) + 0.01 * random_vector(12, 8);
  EXPECT_NEAR(sum.value(x), seams->value(x) + 2 * cloth->value(x) + 0.5 * pins->value(x),
              1e-12 * sum.value(x));
  const VecX g = test::energy_gradient(sum, x);
  EXPECT_LT(check_gradient([&](const VecX& y) { return sum.value(y); }, g, x, 1e-6).relative_error,
            1e-6);
  EXPECT_LT(check_hessian([&](const VecX& y) { return test::energy_gradient(sum, y); },
                          MatX(test::energy_hessian(sum, x)), x, 1e-6)
                .relative_error,
            1e-6);
  EXPECT_THROW(sum.add(nullptr), std::invalid_argument);
}

}  // namespace tightfit::test::seam_pin_sum_test
