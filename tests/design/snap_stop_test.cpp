/// The optimizer on an objective with a cliff (a stand-in for a fit that snaps to another
/// equilibrium): it records the snapped trials and stops at the cliff's edge after
/// `snap_iterations` such iterations, naming the place; with snap_iterations = 0 it
/// creeps on.
#include <gtest/gtest.h>

#include "adjoint_test_scene.hpp"
#include "tightfit/design/pattern_optimizer.hpp"

namespace tightfit::snap_stop_test {

/// T = `height` once the garment's mean z has moved beyond `edge` (m) from `start`, else
/// 0; its gradient is 0: the line search meets the jump only by trying.
class CliffTerm : public DesignTerm {
 public:
  CliffTerm(double start, double edge, double height)
      : start_(start), edge_(edge), height_(height) {}
  std::string name() const override { return "cliff"; }
  double value(const DesignState& s) const override {
    double z = 0.0;
    const Eigen::Index n = s.x.size() / 3;
    for (Eigen::Index i = 0; i < n; ++i) z += s.x[3 * i + 2];
    return z / static_cast<double>(n) - start_ > edge_ ? height_ : 0.0;
  }
  void add_gradient(const DesignState&, VecX&, VecX&) const override {}
  bool depends_on_positions() const override { return true; }

 private:
  double start_, edge_, height_;
};

struct CliffRun {
  OptimizationResult result;
  std::vector<OptimizationIteration> history;
};

CliffRun run_towards_cliff(int snap_iterations) {
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
  objective->add(std::make_shared<CliffTerm>(mean_z, 0.3 * dz, height), 1.0);
  for (const auto& r : test::regularizers(sim.garment())) objective->add(r, 1e-4);
  DesignProblem problem(sim, objective);
  PatternOptimizerOptions options;
  options.max_iterations = 25;
  options.snap_iterations = snap_iterations;
  PatternOptimizer optimizer(problem, options);
  CliffRun run;
  run.result = optimizer.run();
  run.history = optimizer.history();
  return run;
}

TEST(SnapStop, StopsAtTheEdgeOfAJumpAndSaysWhere) {
  const CliffRun run = run_towards_cliff(3);
  std::printf("  %s\n", run.result.stop_reason.c_str());
  ASSERT_EQ(run.result.stop_reason.rfind("snap-through", 0), 0u) << run.result.stop_reason;
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
  EXPECT_EQ(run.result.stop_reason.find("snap-through"), std::string::npos)
      << run.result.stop_reason;
  int snapped = 0;
  for (const OptimizationIteration& it : run.history) snapped += it.snap ? 1 : 0;
  EXPECT_GE(snapped, 3) << "the snaps are still recorded";
}

}  // namespace tightfit::snap_stop_test
