/// L-BFGS pattern optimizer on a small sleeve: monotone decrease on accepted steps,
/// only converged equilibria accepted, survival of failed forward solves, and the
/// optimized pattern actually reaching the objective's optimum.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>

#include "adjoint_test_scene.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/pattern_optimizer.hpp"

namespace tightfit::pattern_optimizer_test {

using test::make_sleeve_scene;

void print_history(const std::vector<OptimizationIteration>& history) {
  for (const OptimizationIteration& it : history)
    std::printf(
        "  it %2d  T %.6e  |g| %.3e  step %.2e m  alpha %.3g  trials %d (failed %d)  "
        "newton %d  %.2f s\n",
        it.iteration, it.value, it.gradient_norm, it.max_point_move, it.step_factor,
        it.line_search_trials, it.failed_solves, it.newton_iterations, it.seconds);
}

/// Every accepted value is strictly below the previous one.
void expect_monotone(const std::vector<OptimizationIteration>& history) {
  for (size_t k = 1; k < history.size(); ++k)
    EXPECT_LT(history[k].value, history[k - 1].value) << "iteration " << history[k].iteration;
}

/// The simulation is at a converged equilibrium of its current rest shape.
void expect_equilibrium(GarmentSimulation& sim) {
  EmbeddedEquilibrium& p = sim.problem();
  const double residual = p.force_norm(p.gradient());
  EXPECT_LE(residual, sim.newton().options().relative_force_tolerance * sim.force_scale());
}

TEST(PatternOptimizer, TargetRunDecreasesMonotonicallyThroughConvergedStates) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  auto objective = std::make_shared<DesignTermSum>();
  // Targets 2 mm along the axis and turned by 1°: reachable only by reshaping the
  // pattern (the end rings are pinned).
  objective->add(
      std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
  for (const auto& r : test::regularizers(sim.garment())) objective->add(r, 1e-4);
  DesignProblem problem(sim, objective);
  PatternOptimizerOptions options;
  options.max_iterations = 15;
  PatternOptimizer optimizer(problem, options);
  int callbacks = 0;
  const OptimizationResult result =
      optimizer.run([&](const OptimizationIteration&) { ++callbacks; });
  print_history(optimizer.history());
  std::printf("  %s; T %.4e -> %.4e\n", result.stop_reason.c_str(), result.initial_value,
              result.final_value);
  EXPECT_EQ(callbacks, static_cast<int>(optimizer.history().size()));
  ASSERT_GE(optimizer.history().size(), 4u);
  expect_monotone(optimizer.history());
  EXPECT_LT(result.final_value, result.initial_value);
  expect_equilibrium(sim);
  // The simulation holds the accepted pattern.
  const Points2 rest = problem.rest_positions(problem.accepted_parameters());
  EXPECT_EQ((sim.garment().rest_positions() - rest).norm(), 0.0);
}

/// The sleeve pulled towards turned targets with steps of up to 20 boundary edges: without
/// the compression bound the first trials of an iteration fold the pattern, so line
/// searches backtrack.
struct FoldingRun {
  std::unique_ptr<test::SleeveScene> scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  std::optional<DesignProblem> problem;
  std::optional<PatternOptimizer> optimizer;

  explicit FoldingRun(double max_compression = 0.0) {
    sim.solve();
    auto objective = std::make_shared<DesignTermSum>();
    objective->add(
        std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
    problem.emplace(sim, objective);
    PatternOptimizerOptions options;
    options.max_iterations = 4;
    options.max_step = 20.0 * problem->mean_boundary_edge();
    options.max_compression = max_compression;
    optimizer.emplace(*problem, options);
  }
};

TEST(DesignProblem, AGradientAfterAFactorizingForwardSolveFactorizesNothingMore) {
  test::SleeveSceneOptions o;
  o.soft_body = true;
  auto scene = make_sleeve_scene(o);
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(
      std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
  DesignProblem problem(sim, objective);
  const VecX p0 = problem.initial_parameters();
  ASSERT_TRUE(problem.evaluate(p0, true).ok);
  problem.accept();
  ASSERT_TRUE(problem.accepted_held_point());
  // A pattern 8 % smaller: the forward solve needs Newton steps of its own.
  const VecX p1 = 0.92 * p0;
  const DesignEvaluation ev = problem.evaluate(p1, true);
  ASSERT_TRUE(ev.ok) << ev.failure;
  ASSERT_GT(ev.factorizations, 0);
  EXPECT_EQ(ev.adjoint_factorizations, 0);
  EXPECT_EQ(ev.adjoint_method, AdjointMethod::kPreconditioned);
  EXPECT_LT(ev.adjoint_residual, 1e-11);
  problem.accept();
  // Held: Newton's matrix at a state before the equilibrium, with the trial's rest shape.
  const std::optional<HeldFactorizationPoint>& held = problem.accepted_held_point();
  ASSERT_TRUE(held);
  EXPECT_EQ(held->parameters, p1);
  bool elsewhere = false;
  for (size_t i = 0; i < held->state.garment.size(); ++i) {
    const SurfacePoint &a = held->state.garment[i], &b = problem.accepted_state().garment[i];
    elsewhere |= a.face != b.face || a.u != b.u || a.v != b.v;
  }
  EXPECT_TRUE(elsewhere);
}

TEST(PatternOptimizer, BacktracksOverFailedForwardSolvesAndFlippedPatterns) {
  FoldingRun run;
  GarmentSimulation& sim = run.sim;
  PatternOptimizer& optimizer = *run.optimizer;
  optimizer.run();
  print_history(optimizer.history());
  int failed = 0;
  for (const OptimizationIteration& it : optimizer.history()) failed += it.failed_solves;
  EXPECT_GT(failed, 0);
  ASSERT_GE(optimizer.history().size(), 3u);
  expect_monotone(optimizer.history());
  expect_equilibrium(sim);
}

/// Signed areas of the pattern triangles at the simulation's current rest shape.
VecX pattern_areas(const GarmentSimulation& sim) {
  const Points2 rest = sim.garment().rest_positions();
  const Triangles& tri = sim.garment().topology->pattern_triangles;
  VecX a(tri.rows());
  for (Eigen::Index t = 0; t < tri.rows(); ++t) {
    const Eigen::RowVector2d e1 = rest.row(tri(t, 1)) - rest.row(tri(t, 0));
    const Eigen::RowVector2d e2 = rest.row(tri(t, 2)) - rest.row(tri(t, 0));
    a[t] = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  }
  return a;
}

TEST(DesignProblem, TheCompressionBoundIsExact) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  DesignProblem problem(sim, std::make_shared<DesignTermSum>());
  const VecX p = problem.initial_parameters();
  const Triangles& tri = sim.garment().topology->pattern_triangles;
  auto areas = [&](const VecX& q) {
    const Points2 rest = problem.rest_positions(q);
    VecX a(tri.rows());
    for (Eigen::Index t = 0; t < tri.rows(); ++t) {
      const Eigen::RowVector2d e1 = rest.row(tri(t, 1)) - rest.row(tri(t, 0));
      const Eigen::RowVector2d e2 = rest.row(tri(t, 2)) - rest.row(tri(t, 0));
      a[t] = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    }
    return a;
  };
  const VecX a0 = areas(p);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::srand(seed);
    const VecX d = VecX::Random(p.size()) * problem.mean_boundary_edge();
    const double alpha = problem.max_step_keeping_areas(p, d, 0.5);
    ASSERT_TRUE(std::isfinite(alpha) && alpha > 0.0);
    const VecX at = areas(p + alpha * d).cwiseQuotient(a0);
    const VecX inside = areas(p + 0.999 * alpha * d).cwiseQuotient(a0);
    EXPECT_NEAR(at.minCoeff(), 0.5, 1e-9);
    EXPECT_GT(inside.minCoeff(), 0.5);
  }
}

TEST(PatternOptimizer, TheTrustRegionKeepsEveryStepFromCrushingATriangle) {
  // The folding run's steps of 20 edges: with the compression bound no trial flips or
  // crushes a triangle, and no accepted step shrinks one below half its area.
  FoldingRun run(0.5);
  VecX before = pattern_areas(run.sim);
  double worst = 1.0;
  run.optimizer->run([&](const OptimizationIteration&) {
    const VecX after = pattern_areas(run.sim);
    worst = std::min(worst, after.cwiseQuotient(before).minCoeff());
    before = after;
  });
  print_history(run.optimizer->history());
  int failed = 0;
  for (const OptimizationIteration& it : run.optimizer->history()) failed += it.failed_solves;
  EXPECT_EQ(failed, 0);
  EXPECT_GE(worst, 0.5 - 1e-9);
  ASSERT_GE(run.optimizer->history().size(), 3u);
  expect_monotone(run.optimizer->history());
}

TEST(PatternOptimizer, AStopRequestEndsALongLineSearchBetweenTrials) {
  // The first trials of iteration 1 fold the pattern (as above), so its line search
  // needs several; a stop requested after the first of them ends the run there, with
  // the pattern and equilibrium of iteration 0.
  FoldingRun run;
  GarmentSimulation& sim = run.sim;
  DesignProblem& problem = *run.problem;
  PatternOptimizer& optimizer = *run.optimizer;
  int polls = 0;  // 1: before iteration 1; 2: before its second trial
  const OptimizationResult result = optimizer.run({}, [&] { return ++polls >= 2; });
  std::printf("  %s\n", result.stop_reason.c_str());
  EXPECT_EQ(polls, 2);
  EXPECT_TRUE(result.interrupted);
  EXPECT_NE(result.stop_reason.find("line search of iteration 1"), std::string::npos)
      << result.stop_reason;
  ASSERT_EQ(optimizer.history().size(), 1u);
  EXPECT_EQ(result.final_value, optimizer.history().front().value);
  expect_equilibrium(sim);
  const Points2 rest = problem.rest_positions(problem.accepted_parameters());
  EXPECT_EQ((sim.garment().rest_positions() - rest).norm(), 0.0);
  EXPECT_EQ((problem.accepted_parameters() - problem.initial_parameters()).norm(), 0.0);
}

/// T = ½‖x − targets‖² whose gradient is NaN: an objective broken in its derivative.
class NanGradientTerm : public test::TargetPositionTerm {
 public:
  using TargetPositionTerm::TargetPositionTerm;
  void add_gradient(const DesignState& s, VecX& d_x, VecX& d_rest) const override {
    TargetPositionTerm::add_gradient(s, d_x, d_rest);
    d_x[0] = std::numeric_limits<double>::quiet_NaN();
  }
};

TEST(PatternOptimizer, NeverAcceptsANonFiniteValueOrGradient) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(std::make_shared<NanGradientTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
  DesignProblem problem(sim, objective);
  const DesignEvaluation e = problem.evaluate(problem.initial_parameters(), true);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.failure.find("not finite"), std::string::npos) << e.failure;
  EXPECT_THROW(problem.accept(), std::logic_error);
  // The optimizer cannot even start from such a pattern: a solver error, no history.
  PatternOptimizer optimizer(problem);
  EXPECT_THROW(optimizer.run(), SolverError);
  EXPECT_TRUE(optimizer.history().empty());
}

TEST(PatternOptimizer, RejectsATrialThatFlipsARestTriangle) {
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(test::regularizers(sim.garment())[0], 1.0);
  DesignProblem problem(sim, objective);
  ASSERT_TRUE(problem.evaluate(problem.initial_parameters()).ok);
  problem.accept();
  // Move one boundary point across the piece.
  VecX p = problem.initial_parameters();
  p[0] += 0.5;
  const DesignEvaluation e = problem.evaluate(p);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.failure.find("flipped"), std::string::npos) << e.failure;
  problem.restore_accepted();
  expect_equilibrium(sim);
}

TEST(PatternOptimizer, RecoversTheShapeOfAnotherPattern) {
  // Targets: the equilibrium of a pattern whose rows are redistributed along the axis
  // (y -> y + 0.15 y (h - y) / h: the middle rows move up by up to 3 mm). Starting from
  // the original pattern, the optimizer must reach them. (Widening the pattern instead
  // would hardly move x on a rigid cylinder: an ill-conditioned target.)
  auto scene = make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  VecX targets;
  {
    DesignProblem probe(sim, std::make_shared<DesignTermSum>());
    VecX shifted = probe.initial_parameters();
    double h = 0.0;
    for (Eigen::Index i = 1; i < shifted.size(); i += 2) h = std::max(h, shifted[i]);
    for (Eigen::Index i = 1; i < shifted.size(); i += 2)
      shifted[i] += 0.15 * shifted[i] * (h - shifted[i]) / h;
    ASSERT_TRUE(probe.evaluate(shifted, false).ok);
    const Points3& x = sim.garment_positions();
    targets = Eigen::Map<const VecX>(x.data(), x.size());
    probe.restore_accepted();
  }
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(std::make_shared<test::TargetPositionTerm>(targets), 1.0);
  DesignProblem problem(sim, objective);
  PatternOptimizerOptions options;
  options.max_iterations = 30;
  PatternOptimizer optimizer(problem, options);
  const OptimizationResult result = optimizer.run();
  print_history(optimizer.history());
  std::printf("  %s; T %.4e -> %.4e m^2 in %d iterations, %.2f s\n", result.stop_reason.c_str(),
              result.initial_value, result.final_value, result.iterations, result.seconds);
  expect_monotone(optimizer.history());
  EXPECT_LT(result.final_value, 1e-4 * result.initial_value);  // measured 4.5e-5
  expect_equilibrium(sim);
}

}  // namespace tightfit::pattern_optimizer_test
