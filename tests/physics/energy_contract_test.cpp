/// Every energy of the physics layer through the one contract (tests/support/
/// energy_contract.hpp): derivatives, symmetry, a sparsity pattern that does not change
/// with the state (here: from stretched to compressed cloth, slack springs), a projected
/// Hessian that is PSD with the same pattern, and the rest derivatives of the
/// rest-dependent energies. A new energy gets a case in kCases.
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "physics_test_util.hpp"
#include "support/energy_contract.hpp"
#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/neo_hookean_energy.hpp"
#include "tightfit/physics/pin_energy.hpp"
#include "tightfit/physics/seam_spring_energy.hpp"
#include "tightfit/physics/sum_energy.hpp"

namespace tightfit::energy_contract_test {

using test::flatten;
using test::random_vector;

/// Two pattern pieces (two triangles each) sewn along one edge (pattern vertices 1, 2
/// and 4, 5 are garment vertices 1, 2), with the seam springs along it.
struct SewnSquares {
  Points2 rest;
  Triangles triangles;
  std::vector<int> to_garment = {0, 1, 2, 3, 1, 4, 5, 2};
  SewnSquares() : rest(8, 2), triangles(4, 3) {
    rest << 0, 0, 0.1, 0, 0.1, 0.1, 0, 0.1, 0, 0, 0.11, 0, 0.11, 0.1, 0, 0.1;
    triangles << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  }
  /// Garment positions (6 vertices): the squares side by side, scaled by `stretch`.
  VecX positions(double stretch, unsigned seed) const {
    Points3 x(6, 3);
    x << 0, 0, 0, 0.1, 0, 0, 0.1, 0.1, 0, 0, 0.1, 0.01, 0.2, 0, 0.02, 0.2, 0.1, 0.03;
    return stretch * flatten(x) + 2e-3 * random_vector(18, seed);
  }
};

/// One energy under test: its states and, for rest-dependent ones, itself as such.
struct Case {
  std::string name;
  std::shared_ptr<Energy> energy;
  VecX x, other;
  RestDependentEnergy* rest_dependent = nullptr;
  /// The rest arrays the garment energies read (kept alive with them).
  std::vector<std::shared_ptr<const Points2>> rests{};
};

Case cloth_case() {
  const SewnSquares s;
  ClothMaterial m;
  m.regime_smoothing = 1e-2;
  auto rest = std::make_shared<const Points2>(s.rest);
  auto e = std::make_shared<ClothEnergy>(s.triangles, *rest, s.to_garment, 6, m);
  return {"cloth", e, s.positions(1.15, 1), s.positions(0.85, 2), e.get(), {rest}};
}

Case seam_case() {
  const SewnSquares s;
  const SeamMaterial material{0.005, 2e-4, 5.4e6};
  auto rest = std::make_shared<const Points2>(s.rest);
  auto e = std::make_shared<SeamSpringEnergy>(polyline_edges({{1, 2}, {4, 7}}), *rest, s.to_garment,
                                              6, material);
  return {"seam springs", e, s.positions(1.1, 3), s.positions(0.9, 4), e.get(), {rest}};
}

Case neo_hookean_case() {
  Points3 rest;
  Tetrahedra tets;
  test::unit_cube_tets(rest, tets);
  auto e = std::make_shared<NeoHookeanEnergy>(rest, tets);
  return {"neo-hookean", e, 1.1 * flatten(rest) + 0.02 * random_vector(24, 5),
          0.95 * flatten(rest) + 0.02 * random_vector(24, 6)};
}

Case pin_case() {
  Points3 targets(2, 3);
  targets << 0.1, 0.2, 0.3, -0.1, 0.0, 0.05;
  return {"pins", std::make_shared<PinEnergy>(std::vector<int>{2, 0}, targets, 1e3),
          random_vector(12, 7), random_vector(12, 8)};
}

Case sum_case() {
  const SewnSquares s;
  auto sum = std::make_shared<SumEnergy>();
  const Case cloth = cloth_case();
  const Case seams = seam_case();
  sum->add(cloth.energy, 2.0);
  sum->add(seams.energy);
  Points3 targets(1, 3);
  targets << 0.0, 0.0, 0.0;
  sum->add(std::make_shared<PinEnergy>(std::vector<int>{0}, targets, 50.0));
  return {"sum",
          sum,
          s.positions(1.15, 9),
          s.positions(0.85, 10),
          nullptr,
          {cloth.rests[0], seams.rests[0]}};
}

const std::vector<std::pair<std::string, std::function<Case()>>> kCases = {
    {"cloth", cloth_case},
    {"seam_springs", seam_case},
    {"neo_hookean", neo_hookean_case},
    {"pins", pin_case},
    {"sum", sum_case}};

class EnergyContract : public ::testing::TestWithParam<size_t> {};

TEST_P(EnergyContract, DerivativesPatternAndProjection) {
  Case c = kCases[GetParam()].second();
  test::expect_energy_contract(*c.energy, c.x, c.other);
  if (c.rest_dependent) {
    test::expect_rest_dependent_contract(*c.rest_dependent, c.x);
    test::expect_rest_dependent_contract(*c.rest_dependent, c.other);
  }
}

INSTANTIATE_TEST_SUITE_P(Physics, EnergyContract, ::testing::Range<size_t>(0, kCases.size()),
                         [](const ::testing::TestParamInfo<size_t>& param) {
                           return kCases[param.param].first;
                         });

}  // namespace tightfit::energy_contract_test
