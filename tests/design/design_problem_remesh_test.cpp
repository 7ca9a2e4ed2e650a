/// DesignProblem::remesh builds a new reference (coordinates, initial pattern, objective)
/// and swaps it in only when the remeshed problem solved: a re-solve that fails leaves
/// the problem exactly as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adjoint_test_scene.hpp"
#include "tightfit/design/optimization_problem.hpp"

namespace tightfit::design_problem_remesh_test {

/// T = ½ Σ (rest y)² over the pattern (m²), or NaN when `poisoned`.
class RestHeightTerm : public DesignTerm {
 public:
  explicit RestHeightTerm(bool poisoned) : poisoned_(poisoned) {}
  std::string name() const override { return "rest height"; }
  double value(const DesignState& s) const override {
    if (poisoned_) return std::numeric_limits<double>::quiet_NaN();
    double t = 0.0;
    for (Eigen::Index v = 0; v < s.rest.rows(); ++v) t += 0.5 * s.rest(v, 1) * s.rest(v, 1);
    return t;
  }
  void add_gradient(const DesignState& s, VecX&, VecX& d_rest) const override {
    for (Eigen::Index v = 0; v < s.rest.rows(); ++v) d_rest[2 * v + 1] += s.rest(v, 1);
  }
  bool depends_on_positions() const override { return false; }

 private:
  bool poisoned_;
};

TEST(DesignProblemRemesh, AFailedReSolveLeavesTheReferenceAndTheAcceptedPoint) {
  test::SleeveSceneOptions so;
  so.jitter = 0.0;
  auto scene = test::make_sleeve_scene(so);
  GarmentSimulation& sim = *scene->sim;
  sim.solve();
  int calls = 0;
  auto factory = [&](const GarmentSimulation&) {
    auto sum = std::make_shared<DesignTermSum>();
    sum->add(std::make_shared<RestHeightTerm>(++calls > 1), 1.0);
    return sum;
  };
  DesignProblem problem(sim, factory(sim), {}, factory);
  const VecX p0 = problem.initial_parameters();
  const DesignEvaluation before = problem.evaluate(p0, true);
  ASSERT_TRUE(before.ok) << before.failure;
  problem.accept();
  const int vertices = sim.garment().num_garment_vertices();
  const Points2 rest = problem.rest_positions(p0);
  const double edge = problem.mean_boundary_edge();

  // The remeshed garment is built and its objective too, but T is not finite there.
  const RemeshOutcome out = problem.remesh({0});
  EXPECT_FALSE(out.ok);
  EXPECT_NE(out.failure.find("re-solve after remeshing"), std::string::npos) << out.failure;
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(sim.garment().num_garment_vertices(), vertices);
  ASSERT_EQ(problem.num_parameters(), p0.size());
  EXPECT_EQ(problem.initial_parameters(), p0);
  EXPECT_EQ(problem.accepted_parameters(), p0);
  EXPECT_EQ(problem.rest_positions(p0), rest);
  EXPECT_EQ(problem.mean_boundary_edge(), edge);
  EXPECT_FALSE(problem.remeshed_design().has_value());
  const DesignEvaluation after = problem.evaluate(p0, true);
  ASSERT_TRUE(after.ok) << after.failure;
  EXPECT_NEAR(after.value, before.value, 1e-12 * std::abs(before.value));
}

TEST(DesignProblemRemesh, AFactoryThatThrowsOnRestoreLeavesTheSimulationAsItWas) {
  test::SleeveSceneOptions so;
  so.jitter = 0.0;
  auto factory = [](const GarmentSimulation&) {
    auto sum = std::make_shared<DesignTermSum>();
    sum->add(std::make_shared<RestHeightTerm>(false), 1.0);
    return sum;
  };
  // A remeshed design and its state, as a checkpoint holds them.
  auto source = test::make_sleeve_scene(so);
  source->sim->solve();
  DesignProblem remeshed(*source->sim, factory(*source->sim), {}, factory);
  ASSERT_TRUE(remeshed.evaluate(remeshed.initial_parameters(), true).ok);
  remeshed.accept();
  ASSERT_TRUE(remeshed.remesh({0}).ok);
  const std::optional<RemeshedDesign> design = remeshed.remeshed_design();
  ASSERT_TRUE(design.has_value());
  const EmbeddedState state = source->sim->problem().state();

  // Resuming into a fresh problem whose factory fails for the remeshed garment.
  auto scene = test::make_sleeve_scene(so);
  GarmentSimulation& sim = *scene->sim;
  int calls = 0;
  auto failing = [&](const GarmentSimulation& s) -> std::shared_ptr<DesignTermSum> {
    if (++calls > 1) throw InputError("test factory", "no terms for this garment");
    return factory(s);
  };
  DesignProblem problem(sim, failing(sim), {}, failing);
  const int vertices = sim.garment().num_garment_vertices();
  const std::vector<SurfacePoint> embedding = sim.problem().state().garment;
  EXPECT_THROW(problem.restore_remeshed_design(*design, state), InputError);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(sim.garment().num_garment_vertices(), vertices);
  ASSERT_EQ(sim.problem().state().garment.size(), embedding.size());
  for (size_t i = 0; i < embedding.size(); ++i) {
    EXPECT_EQ(sim.problem().state().garment[i].face, embedding[i].face);
    EXPECT_EQ(sim.problem().state().garment[i].u, embedding[i].u);
  }
  EXPECT_FALSE(problem.remeshed_design().has_value());
}

}  // namespace tightfit::design_problem_remesh_test
