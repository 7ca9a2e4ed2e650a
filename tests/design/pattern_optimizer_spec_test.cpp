/// The scene's "optimize" section: defaults, units, strictness.
#include <gtest/gtest.h>

#include "tightfit/common/error.hpp"
#include "tightfit/design/optimization_spec.hpp"

namespace tightfit::pattern_optimizer_spec_test {

OptimizationSpec parse(const std::string& text) {
  return parse_optimization_spec(nlohmann::json::parse(text), "scene.json", "/optimize", "/scenes");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OptimizationSpec, ReadsObjectivesRegularizersAndSettings) {
  const OptimizationSpec s = parse(R"({
    "objectives": {"stretch": {"weight": 2, "min": 1.05, "max": 1.3},
                   "shape": {"target": "t.obj", "radius": 0.02},
                   "pressure": {"min_mmhg": 15, "max_mmhg": 25},
                   "seam_traction": {"weight": 0.5}},
    "regularizers": {"seam_length": 1, "boundary_smoothness": 1e-4, "pinned_traction": 0.01,
                     "compactness": {"weight": 3, "min_ratio": 0.2, "pair_stride": 2}},
    "max_iterations": 7, "checkpoint_every": 2, "min_area_ratio": 0.1,
    "lbfgs": {"memory": 5, "max_step": 0.002}})");
  ASSERT_TRUE(s.stretch);
  EXPECT_EQ(s.stretch->weight, 2.0);
  EXPECT_EQ(s.stretch->min_stretch, 1.05);
  EXPECT_EQ(*s.stretch->max_stretch, 1.3);
  ASSERT_TRUE(s.shape);
  EXPECT_EQ(s.shape->weight, 1.0);
  EXPECT_EQ(s.shape->target, std::filesystem::path("/scenes/t.obj"));
  EXPECT_EQ(s.shape->radius, 0.02);
  EXPECT_FALSE(s.shape->skip_pinned);
  ASSERT_TRUE(s.pressure);
  EXPECT_NEAR(s.pressure->min_pa, 15 * 133.322387415, 1e-9);
  EXPECT_NEAR(s.pressure->max_pa, 25 * 133.322387415, 1e-9);
  EXPECT_EQ(s.seam_traction->weight, 0.5);
  EXPECT_EQ(s.regularizers.seam_length, 1.0);
  EXPECT_EQ(s.regularizers.boundary_spacing, 0.0);
  EXPECT_EQ(s.regularizers.boundary_smoothness, 1e-4);
  EXPECT_EQ(s.regularizers.pinned_traction, 0.01);
  EXPECT_EQ(s.regularizers.compactness, 3.0);
  EXPECT_EQ(s.regularizers.compactness_options.min_ratio, 0.2);
  EXPECT_EQ(s.regularizers.compactness_options.pair_stride, 2);
  EXPECT_EQ(s.optimizer.max_iterations, 7);
  EXPECT_EQ(s.checkpoint_every, 2);
  EXPECT_EQ(s.problem.min_area_ratio, 0.1);
  EXPECT_EQ(s.optimizer.memory, 5);
  EXPECT_EQ(s.optimizer.max_step, 0.002);
}

TEST(OptimizationSpec, DefaultsAndOpenUpperStretchBound) {
  const OptimizationSpec s = parse(R"({"objectives": {"stretch": {"min": 1.02}}})");
  EXPECT_FALSE(s.stretch->max_stretch);
  EXPECT_EQ(s.optimizer.max_iterations, 50);
  EXPECT_EQ(s.checkpoint_every, 5);
  EXPECT_FALSE(s.shape);
}

TEST(OptimizationSpec, ShapeObjectiveCanSkipThePinnedVertices) {
  const OptimizationSpec s =
      parse(R"({"objectives": {"shape": {"target": "t.obj", "vertices": "unpinned"}}})");
  EXPECT_TRUE(s.shape->skip_pinned);
  EXPECT_NE(error_of(R"({"objectives": {"shape": {"target": "t.obj", "vertices": "some"}}})")
                .find("/optimize/objectives/shape/vertices"),
            std::string::npos);
}

TEST(OptimizationSpec, ReadsADirectionalStretchObjective) {
  const OptimizationSpec s = parse(R"({"objectives": {"directional_stretch":
      {"weight": 3, "direction": "across_grain", "min": 1.28, "max": 1.32}}})");
  ASSERT_TRUE(s.directional_stretch);
  EXPECT_TRUE(s.directional_stretch->across_grain);
  EXPECT_EQ(s.directional_stretch->bounds.weight, 3.0);
  EXPECT_EQ(s.directional_stretch->bounds.min_stretch, 1.28);
  EXPECT_EQ(*s.directional_stretch->bounds.max_stretch, 1.32);
  const OptimizationSpec along =
      parse(R"({"objectives": {"directional_stretch": {"direction": "along_grain", "min": 1.1}}})");
  EXPECT_FALSE(along.directional_stretch->across_grain);
  EXPECT_FALSE(along.directional_stretch->bounds.max_stretch);
  EXPECT_NE(error_of(R"({"objectives": {"directional_stretch": {"min": 1.3}}})")
                .find("/optimize/objectives/directional_stretch"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"directional_stretch":
                {"direction": "bias", "min": 1.3}}})")
                .find("/optimize/objectives/directional_stretch/direction"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"directional_stretch":
                {"direction": "along_grain", "min": 1.3, "max": 1.2}}})")
                .find("/optimize/objectives/directional_stretch/max"),
            std::string::npos);
}

TEST(OptimizationSpec, RemeshOptionsHaveDefaultsAndAreRead) {
  const OptimizationSpec d = parse(R"({"objectives": {"stretch": {}}})");
  EXPECT_TRUE(d.problem.remesh.enabled);
  EXPECT_EQ(d.problem.remesh.min_angle_deg, 10.0);
  EXPECT_EQ(d.problem.remesh.min_area_fraction, 0.1);
  EXPECT_EQ(d.problem.remesh.edge_length, 0.0);
  const OptimizationSpec s = parse(R"({"objectives": {"stretch": {}},
    "remesh": {"enabled": false, "min_angle_deg": 20, "min_area_fraction": 0.05,
               "edge_length": 0.01, "smoothing_iterations": 3}})");
  EXPECT_FALSE(s.problem.remesh.enabled);
  EXPECT_EQ(s.problem.remesh.min_angle_deg, 20.0);
  EXPECT_EQ(s.problem.remesh.min_area_fraction, 0.05);
  EXPECT_EQ(s.problem.remesh.edge_length, 0.01);
  EXPECT_EQ(s.problem.remesh.smoothing_iterations, 3);
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {}}, "remesh": {"min_angle_deg": 70}})")
                .find("/optimize/remesh/min_angle_deg"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {}}, "remesh": {"angle": 10}})")
                .find("unknown key \"angle\""),
            std::string::npos);
}

TEST(OptimizationSpec, RejectsBadInputNamingThePath) {
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {"min": 1.1, "max": 1.0}}})")
                .find("/optimize/objectives/stretch/max"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"strech": {}}})").find("unknown key \"strech\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {"weight": -1}}})").find("/weight"),
            std::string::npos);
  EXPECT_NE(
      error_of(R"({"objectives": {"pressure": {"min_pa": 1, "max_mmhg": 2}}})").find("either"),
      std::string::npos);
  EXPECT_NE(error_of(R"({"regularizers": {"seam_length": 0}})").find("no objective"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {}}, "checkpoint_every": 0})")
                .find("/optimize/checkpoint_every"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"stretch": {}}, "lbfgs": {"memory": "8"}})")
                .find("/optimize/lbfgs/memory"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"objectives": {"shape": {"target": ""}}})").find("/target"),
            std::string::npos);
}

}  // namespace tightfit::pattern_optimizer_spec_test
