/// Each stopping rule of PatternOptimizer on the small sleeve, named by the result and
/// in result.stop_reason: the gradient rule, the target value, no progress with a
/// gradient that agrees with finite differences (a stationary point) and with one that
/// does not (a wrong gradient), the iteration limit and the time limit.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "adjoint_test_scene.hpp"
#include "tightfit/design/pattern_optimizer.hpp"

namespace tightfit::stop_rules_test {

/// TargetPositionTerm with its gradient doubled: a descent direction still, but not the
/// derivative of the value (the finite-difference check must catch it).
class WrongGradientTerm : public test::TargetPositionTerm {
 public:
  using TargetPositionTerm::TargetPositionTerm;
  void add_gradient(const DesignState& s, VecX& d_x, VecX& d_rest) const override {
    TargetPositionTerm::add_gradient(s, d_x, d_rest);
    TargetPositionTerm::add_gradient(s, d_x, d_rest);
  }
};

struct StopRun {
  OptimizationResult result;
  std::vector<OptimizationIteration> history;
};

/// The sleeve pulled towards targets turned by 1° and 2 mm along its axis.
StopRun run_sleeve(const PatternOptimizerOptions& options, bool wrong_gradient = false) {
  auto scene = test::make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  auto objective = std::make_shared<DesignTermSum>();
  const VecX targets = test::turned_targets(sim, 0.0175, 0.002);
  if (wrong_gradient)
    objective->add(std::make_shared<WrongGradientTerm>(targets), 1.0);
  else
    objective->add(std::make_shared<test::TargetPositionTerm>(targets), 1.0);
  DesignProblem problem(sim, objective);
  PatternOptimizer optimizer(problem, options);
  StopRun run;
  run.result = optimizer.run();
  run.history = optimizer.history();
  std::printf("  %s after %d iterations: %s\n", stop_rule_name(run.result.rule),
              run.result.iterations, run.result.stop_reason.c_str());
  return run;
}

TEST(StopRules, GradientBelowItsRelativeTolerance) {
  PatternOptimizerOptions o;
  o.max_iterations = 60;
  o.relative_gradient_tolerance = 0.05;
  const StopRun run = run_sleeve(o);
  ASSERT_EQ(run.result.rule, StopRule::kGradient);
  EXPECT_TRUE(run.result.converged);
  EXPECT_LE(run.history.back().gradient_norm, 0.05 * run.history.front().gradient_norm);
  for (size_t k = 0; k + 1 < run.history.size(); ++k)
    EXPECT_GT(run.history[k].gradient_norm, 0.05 * run.history.front().gradient_norm);
  EXPECT_EQ(run.result.stop_reason.rfind("converged: the gradient norm", 0), 0u);
}

TEST(StopRules, TargetValue) {
  PatternOptimizerOptions o;
  o.max_iterations = 60;
  o.relative_gradient_tolerance = 0.0;
  const StopRun probe = run_sleeve([] {
    PatternOptimizerOptions p;
    p.max_iterations = 0;
    return p;
  }());
  o.value_tolerance = 0.5 * probe.result.initial_value;
  const StopRun run = run_sleeve(o);
  ASSERT_EQ(run.result.rule, StopRule::kTargetValue);
  EXPECT_TRUE(run.result.converged);
  EXPECT_LE(run.result.final_value, o.value_tolerance);
}

TEST(StopRules, NoProgressWithAnAgreeingGradientIsStationary) {
  PatternOptimizerOptions o;
  o.max_iterations = 60;
  o.relative_gradient_tolerance = 0.0;
  // Any decrease below 100 % over 2 iterations counts as "no progress": the rule fires
  // after two iterations and checks the gradient there.
  o.stall_iterations = 2;
  o.relative_decrease_tolerance = 1.0;
  const StopRun run = run_sleeve(o);
  ASSERT_EQ(run.result.rule, StopRule::kStationary) << run.result.stop_reason;
  EXPECT_TRUE(run.result.converged);
  EXPECT_EQ(run.result.iterations, 2);
  ASSERT_EQ(run.result.gradient_check.size(), 3u);
  for (const DirectionalCheck& c : run.result.gradient_check)
    EXPECT_LT(c.relative_error, 0.05) << c.adjoint << " vs " << c.finite_difference;
}

TEST(StopRules, NoProgressWithAWrongGradientIsNotConverged) {
  PatternOptimizerOptions o;
  o.max_iterations = 60;
  o.relative_gradient_tolerance = 0.0;
  o.stall_iterations = 2;
  o.relative_decrease_tolerance = 1.0;
  const StopRun run = run_sleeve(o, true);
  ASSERT_EQ(run.result.rule, StopRule::kNoProgress) << run.result.stop_reason;
  EXPECT_FALSE(run.result.converged);
  ASSERT_EQ(run.result.gradient_check.size(), 3u);
  for (const DirectionalCheck& c : run.result.gradient_check)
    EXPECT_NEAR(c.adjoint / c.finite_difference, 2.0, 0.1);
  EXPECT_NE(run.result.stop_reason.find("disagrees with finite differences"), std::string::npos);
}

TEST(StopRules, IterationLimit) {
  PatternOptimizerOptions o;
  o.max_iterations = 3;
  const StopRun run = run_sleeve(o);
  ASSERT_EQ(run.result.rule, StopRule::kIterationLimit);
  EXPECT_FALSE(run.result.converged);
  EXPECT_EQ(run.result.iterations, 3);
  EXPECT_EQ(run.result.stop_reason.rfind("not converged: the iteration limit", 0), 0u);
}

TEST(StopRules, TimeLimit) {
  PatternOptimizerOptions o;
  o.max_iterations = 60;
  o.time_limit = 1e-9;  // spent by the initial evaluation already
  const StopRun run = run_sleeve(o);
  ASSERT_EQ(run.result.rule, StopRule::kTimeLimit);
  EXPECT_FALSE(run.result.converged);
  EXPECT_EQ(run.result.iterations, 0);
  EXPECT_EQ(run.result.stop_reason.rfind("not converged: the time limit", 0), 0u);
}

}  // namespace tightfit::stop_rules_test
