/// Every design term that a garment alone defines, through the one contract
/// (tests/support/energy_contract.hpp): ∂T/∂x and ∂T/∂Xbar against finite differences,
/// and no ∂T/∂x from a term that says it does not depend on positions. The terms that
/// need a simulation (pinned traction, sliding, every-pose terms) are checked through the
/// whole pipeline in their own tests (tests/objectives/sliding_objective_test.cpp,
/// all_poses). A new term gets a case in kTerms.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <numbers>

#include "objective_test_garments.hpp"
#include "support/energy_contract.hpp"
#include "tightfit/objectives/directional_stretch_objective.hpp"
#include "tightfit/objectives/pressure_objective.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/regularizer_corner_angle.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/regularizer_smoothness.hpp"
#include "tightfit/objectives/seam_traction_objective.hpp"
#include "tightfit/objectives/shape_objective.hpp"
#include "tightfit/objectives/stretch_objective.hpp"
#include "tightfit/physics/fabric_law.hpp"

namespace tightfit::design_term_contract_test {

using TermFactory = std::function<std::shared_ptr<const DesignTerm>(const Garment&)>;

/// A sphere of radius 0.06 m about the sleeve's middle, sampled at about 5 mm.
ImlsSurface sphere_target() {
  const test::OrientedPoints sphere = test::fibonacci_sphere(Vec3(0, 0, 0.05), 0.06, 2000);
  return ImlsSurface(sphere.points, sphere.normals, 0.008);
}

/// A measured knit with unloading branches and coupling (physics/fabric_law.hpp).
ClothMaterial measured_knit() {
  ClothMaterial m;
  m.thickness = 5e-4;
  m.measured = std::make_shared<MeasuredFabric>(
      MeasuredFabric{"knit", FabricCurve({0.0, 0.1, 0.3, 0.6}, {0.0, 20.0, 90.0, 300.0}),
                     FabricCurve({0.0, 0.1, 0.3, 0.6}, {0.0, 10.0, 50.0, 160.0}),
                     FabricCurve({0.0, 0.1, 0.3, 0.6}, {0.0, 14.0, 70.0, 260.0}),
                     FabricCurve({0.0, 0.1, 0.3, 0.6}, {0.0, 7.0, 40.0, 140.0}), 0.2, 25.0});
  return m;
}

const std::vector<std::pair<std::string, TermFactory>> kTerms = {
    {"stretch",
     [](const Garment& g) {
       return std::make_shared<StretchObjective>(g, StretchBounds{1.0, 1.05});
     }},
    {"directional_stretch",
     [](const Garment& g) {
       return std::make_shared<DirectionalStretchObjective>(g, FabricDirection::kAcrossGrain,
                                                            StretchBounds{1.0, 1.05});
     }},
    {"pressure",
     [](const Garment& g) {
       return std::make_shared<PressureObjective>(g, ClothMaterial{}, 200.0, 800.0);
     }},
    {"pressure_measured_knit",
     [](const Garment& g) {
       return std::make_shared<PressureObjective>(g, measured_knit(), 200.0, 800.0);
     }},
    {"seam_traction",
     [](const Garment& g) { return std::make_shared<SeamTractionObjective>(g, ClothMaterial{}); }},
    {"seam_traction_measured_knit",
     [](const Garment& g) { return std::make_shared<SeamTractionObjective>(g, measured_knit()); }},
    {"shape",
     [](const Garment& g) {
       return std::make_shared<ShapeObjective>(sphere_target(), g.num_garment_vertices());
     }},
    {"seam_length",
     [](const Garment& g) {
       return std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(g));
     }},
    {"boundary_spacing",
     [](const Garment& g) {
       return std::make_shared<EdgeLengthDifferenceTerm>(even_spacing_regularizer(g));
     }},
    {"boundary_smoothness",
     [](const Garment& g) { return std::make_shared<BoundarySmoothnessRegularizer>(g); }},
    {"corner_angle", [](const Garment& g) { return std::make_shared<CornerAngleRegularizer>(g); }},
    {"compactness",
     [](const Garment& g) {
       return std::make_shared<CompactnessRegularizer>(g, CompactnessOptions{0.5, 1});
     }},
};

class DesignTermContract : public ::testing::TestWithParam<size_t> {};

TEST_P(DesignTermContract, GradientsMatchFiniteDifferences) {
  const test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, 0.1, 0.2, 4);
  const auto term = kTerms[GetParam()].second(s.garment);
  test::ContractTolerances tol;
  tol.step = 1e-7;
  for (unsigned seed = 1; seed <= 2; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    // Moved off the initial pattern, where the regularizers are at their minimum.
    const VecX x = test::perturb(s.x, 0.004, seed);
    const Points2 rest = test::perturb(s.garment.rest_positions(), 0.003, seed + 10);
    EXPECT_GT(term->value(DesignState{x, rest}), 0.0) << "a term at zero checks nothing";
    test::expect_design_term_contract(*term, x, rest, nullptr, tol);
  }
}

INSTANTIATE_TEST_SUITE_P(Terms, DesignTermContract, ::testing::Range<size_t>(0, kTerms.size()),
                         [](const ::testing::TestParamInfo<size_t>& param) {
                           return kTerms[param.param].first;
                         });

}  // namespace tightfit::design_term_contract_test
