/// The optimizer on an objective with a cliff (a stand-in for a fit that snaps to another
/// equilibrium): it records the snapped trials; without jumps it stops at the cliff's
/// edge after `snap_iterations` such iterations, naming the place; with snap_iterations
/// = 0 it creeps on. With jumps it crosses the cliff and goes on from there to a design
/// below the edge's objective; stopped right after a jump it returns the best design,
/// the one at the edge.
#include <gtest/gtest.h>

#include "adjoint_test_scene.hpp"
#include "tightfit/design/pattern_optimizer.hpp"

namespace tightfit::snap_stop_test {

/// T = `height` while the garment's mean z has moved beyond `edge` (m) from `start` but
/// not beyond `end`, else 0; its gradient is 0: the line search meets the jump only by
/// trying.
class CliffTerm : public DesignTerm {
 public:
  CliffTerm(double start, double edge, double height, double end = 1e300)
      : start_(start), edge_(edge), height_(height), end_(end) {}
  std::string name() const override { return "cliff"; }
  double value(const DesignState& s) const override {
    double z = 0.0;
    const Eigen::Index n = s.x.size() / 3;
    for (Eigen::Index i = 0; i < n; ++i) z += s.x[3 * i + 2];
    const double moved = z / static_cast<double>(n) - start_;
    return moved > edge_ && moved <= end_ ? height_ : 0.0;
  }
  void add_gradient(const DesignState&, VecX&, VecX&) const override {}
  bool depends_on_positions() const override { return true; }

 private:
  double start_, edge_, height_, end_;
};

struct CliffRun {
  OptimizationResult result;
  std::vector<OptimizationIteration> history;
  double value_at_end = 0.0;  ///< T of the design the problem holds after run()
  double moved_at_end = 0.0;  ///< how far its mean z moved from the start (m)
};

/// `ridge_end`: where the band of higher T ends (as a fraction of the 2 mm target shift;
/// ≥ 1: never within reach).
/// `stop_after_jump`: a stop request right after the first jump.
CliffRun run_towards_cliff(int snap_iterations, int snap_jumps = 0, double ridge_end = 1e9,
                           bool stop_after_jump = false) {
  auto scene = test::make_sleeve_scene();
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  const Points3& x = sim.garment_positions();
  const double mean_z = x.col(2).mean();
  const double dz = 0.002;  // the targets lie 2 mm along the axis; the cliff at 0.6 mm
  auto objective = std::make_shared<DesignTermSum>();
  auto target = std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0, dz));
  objective->add(target, 1.0);
  // As high as the target term at the start (½ Σ dz²): a trial beyond the cliff rises.
  const double height = 0.5 * static_cast<double>(x.rows()) * dz * dz;
  objective->add(std::make_shared<CliffTerm>(mean_z, 0.3 * dz, height, ridge_end * dz), 1.0);
  for (const auto& r : test::regularizers(sim.garment())) objective->add(r, 1e-4);
  DesignProblem problem(sim, objective);
  PatternOptimizerOptions options;
  options.max_iterations = 25;
  options.snap_iterations = snap_iterations;
  options.snap_jumps = snap_jumps;
  PatternOptimizer optimizer(problem, options);
  CliffRun run;
  run.result = optimizer.run({}, [&] {
    return stop_after_jump && !optimizer.history().empty() && optimizer.history().back().jump;
  });
  run.history = optimizer.history();
  run.moved_at_end = sim.garment_positions().col(2).mean() - mean_z;
  const DesignEvaluation end = problem.evaluate(problem.accepted_parameters(), false);
  EXPECT_TRUE(end.ok) << end.failure;
  run.value_at_end = end.value;
  for (const OptimizationIteration& it : run.history)
    std::printf("  it %2d  T %.6e%s%s\n", it.iteration, it.value, it.snap ? "  snapped" : "",
                it.jump ? "  JUMP" : "");
  std::printf("  %s; best iteration %d, T %.6e (last %.6e)\n", run.result.stop_reason.c_str(),
              run.result.best_iteration, run.result.final_value, run.result.last_value);
  return run;
}

TEST(SnapStop, StopsAtTheEdgeOfAJumpAndSaysWhere) {
  const CliffRun run = run_towards_cliff(3);
  std::printf("  %s\n", run.result.stop_reason.c_str());
  ASSERT_EQ(run.result.rule, StopRule::kSnapThrough) << run.result.stop_reason;
  EXPECT_NE(run.result.stop_reason.find("garment vertex"), std::string::npos);
  EXPECT_FALSE(run.result.converged);
  ASSERT_GE(run.history.size(), 4u);
  for (size_t k = run.history.size() - 3; k < run.history.size(); ++k) {
    const OptimizationIteration& it = run.history[k];
    ASSERT_TRUE(it.snap) << "iteration " << it.iteration;
    EXPECT_GE(it.snap->trials, 2);
    EXPECT_GT(it.snap->rise, 0.0);
    EXPECT_GT(it.snap->step, 0.0);
    EXPECT_GE(it.snap->vertex, 0);
  }
  for (size_t k = 1; k < run.history.size(); ++k)
    EXPECT_LT(run.history[k].value, run.history.front().value)
        << "iteration " << run.history[k].iteration << " accepted beyond the cliff";
}

TEST(SnapStop, ZeroSnapIterationsNeverStopsForIt) {
  const CliffRun run = run_towards_cliff(0);
  EXPECT_NE(run.result.rule, StopRule::kSnapThrough) << run.result.stop_reason;
  int snapped = 0;
  for (const OptimizationIteration& it : run.history) snapped += it.snap ? 1 : 0;
  EXPECT_GE(snapped, 3) << "the snaps are still recorded";
}

TEST(SnapStop, JumpsAndGoesOnToEndBelowTheEdge) {
  const CliffRun run = run_towards_cliff(3, 3, 0.32);
  int jumps = 0;
  double edge = run.history.front().value;  // T at the last point before the first jump
  for (const OptimizationIteration& it : run.history) {
    if (it.jump) {
      ++jumps;
      break;
    }
    edge = it.value;
  }
  ASSERT_GE(jumps, 1);
  EXPECT_NE(run.result.rule, StopRule::kSnapThrough) << run.result.stop_reason;
  EXPECT_LT(run.result.final_value, edge);
  std::printf("  mean z moved %.3f mm at the end (edge 0.6 mm, ridge end 0.64 mm)\n",
              1e3 * run.moved_at_end);
  EXPECT_FALSE(run.result.best_restored);
  EXPECT_NEAR(run.value_at_end, run.result.final_value, 1e-6 * run.result.initial_value);
}

TEST(SnapStop, AJumpThatNeverPaysOffReturnsTheBestDesign) {
  const CliffRun run = run_towards_cliff(3, 1, 1e9, true);
  int jumps = 0;
  for (const OptimizationIteration& it : run.history) jumps += it.jump ? 1 : 0;
  ASSERT_EQ(jumps, 1);
  EXPECT_TRUE(run.result.best_restored);
  EXPECT_LT(run.result.final_value, run.result.last_value);
  // The design the problem holds is the best iteration's, at its objective.
  double best = run.history.front().value;
  for (const OptimizationIteration& it : run.history) best = std::min(best, it.value);
  EXPECT_EQ(run.result.final_value, best);
  EXPECT_NEAR(run.value_at_end, best, 1e-6 * best);
  EXPECT_EQ(run.history[static_cast<size_t>(run.result.best_iteration)].value, best);
}

}  // namespace tightfit::snap_stop_test
