/// Checkpoints of the pattern optimizer: exact JSON round trip, strict reading, and a
/// resumed run that continues exactly like an uninterrupted one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "design/adjoint_test_scene.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"

namespace tightfit::pattern_optimizer_checkpoint_test {

namespace fs = std::filesystem;

std::shared_ptr<DesignTermSum> target_objective(GarmentSimulation& sim) {
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(
      std::make_shared<test::TargetPositionTerm>(test::turned_targets(sim, 0.0175, 0.002)), 1.0);
  for (const auto& r : test::regularizers(sim.garment())) objective->add(r, 1e-4);
  return objective;
}

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_checkpoint_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

TEST(OptimizationCheckpoint, JsonRoundTripIsExact) {
  OptimizationCheckpoint c;
  c.iteration = 2;
  c.parameters = VecX::LinSpaced(6, 0.1, 0.7) / 3.0;
  c.state.garment = {{3, 1.0 / 3.0, 0.2}, {7, 0.0, 0.999999999999}};
  c.state.body = Points3::Random(4, 3);
  c.memory.s = {VecX::Random(6)};
  c.memory.y = {VecX::Random(6)};
  OptimizationIteration it;
  it.iteration = 2;
  it.value = 1.0 / 7.0;
  it.term_values = {0.1, 1.0 / 7.0 - 0.1};
  it.gradient_norm = 3e-9;
  it.seconds = 1.25;
  it.chord_steps = 4;
  it.force_accepted_steps = 2;
  c.history = {it, it};
  SnapRecord snap;
  snap.trials = 3;
  snap.rise = 1.0 / 3.0;
  snap.step = 2e-4;
  snap.move = 0.0107;
  snap.vertex = 8;
  snap.position = Vec3(0.1, 1.0 / 7.0, -0.2);
  snap.label = "pieces 'left_front', 'right_front'";
  c.history[1].snap = snap;
  c.held_ordering.permutation = {2, 0, 3, 1};
  c.held_ordering.factor_nonzeros = 7.0;
  c.held_point = HeldFactorizationPoint{c.parameters * 0.9, c.state, 1.0 / 3.0};
  c.held_point->state.garment[1].v = 0.5 / 3.0;
  const std::vector<std::string> names{"stretch", "seam length"};
  const fs::path file = scratch("roundtrip.json");
  write_checkpoint(file, c, names);
  const OptimizationCheckpoint r = read_checkpoint(file, names);
  EXPECT_EQ(r.iteration, 2);
  EXPECT_EQ(r.parameters, c.parameters);
  ASSERT_EQ(r.state.garment.size(), 2u);
  EXPECT_EQ(r.state.garment[0].u, 1.0 / 3.0);
  EXPECT_EQ(r.state.garment[1].face, 7);
  EXPECT_EQ(r.state.body, c.state.body);
  EXPECT_EQ(r.memory.s[0], c.memory.s[0]);
  EXPECT_EQ(r.memory.y[0], c.memory.y[0]);
  ASSERT_EQ(r.history.size(), 2u);
  EXPECT_EQ(r.history[1].term_values, it.term_values);
  EXPECT_EQ(r.history[1].value, it.value);
  EXPECT_EQ(r.history[1].chord_steps, 4);
  EXPECT_EQ(r.history[1].force_accepted_steps, 2);
  EXPECT_FALSE(r.history[0].snap);
  ASSERT_TRUE(r.history[1].snap);
  EXPECT_EQ(r.history[1].snap->trials, 3);
  EXPECT_EQ(r.history[1].snap->rise, 1.0 / 3.0);
  EXPECT_EQ(r.history[1].snap->move, 0.0107);
  EXPECT_EQ(r.history[1].snap->vertex, 8);
  EXPECT_EQ(r.history[1].snap->position, snap.position);
  EXPECT_EQ(r.history[1].snap->label, snap.label);
  EXPECT_EQ(r.held_ordering.permutation, c.held_ordering.permutation);
  EXPECT_EQ(r.held_ordering.factor_nonzeros, 7.0);
  ASSERT_TRUE(r.held_point);
  EXPECT_EQ(r.held_point->parameters, c.held_point->parameters);
  EXPECT_EQ(r.held_point->state.garment[1].v, 0.5 / 3.0);
  EXPECT_EQ(r.held_point->state.body, c.state.body);
  EXPECT_EQ(r.held_point->shift, 1.0 / 3.0);

  EXPECT_THROW(read_checkpoint(file, {"stretch"}), InputError);  // other objective
  std::ofstream(file) << R"({"format": "something else"})";
  try {
    read_checkpoint(file, names);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/format"), std::string::npos) << e.what();
  }
  // An ordering that is not a permutation would make CHOLMOD read out of bounds.
  for (const char* bad : {"[0, 0, 1]", "[0, 3, 1]", "[0, -1, 1]"}) {
    nlohmann::json j = checkpoint_json(c, names);
    j["held_ordering"]["permutation"] = nlohmann::json::parse(bad);
    try {
      checkpoint_from_json(j, names, "checkpoint.json");
      FAIL() << "expected an InputError for " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/held_ordering/permutation/1"), std::string::npos)
          << e.what();
    }
  }
  // A held point of another design, or with a negative shift, names where it is wrong.
  for (const auto& [key, value, where] :
       {std::tuple{"parameters", nlohmann::json::array({0.1, 0.2}), "/held_point/parameters"},
        std::tuple{"shift", nlohmann::json(-1.0), "/held_point/shift"}}) {
    nlohmann::json j = checkpoint_json(c, names);
    j["held_point"][key] = value;
    try {
      checkpoint_from_json(j, names, "checkpoint.json");
      FAIL() << "expected an InputError for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  }
  fs::remove_all(file.parent_path());
}

TEST(OptimizationCheckpoint, TermNamesAreMadeUnique) {
  auto scene = test::make_sleeve_scene();
  const auto regs = test::regularizers(scene->sim->garment());
  DesignTermSum sum;
  sum.add(regs[0], 1.0);
  sum.add(regs[0], 2.0);
  sum.add(regs[1], 1.0);
  EXPECT_EQ(term_names(sum),
            (std::vector<std::string>{"seam length", "seam length 2", "boundary spacing"}));
}

/// On a rigid body the Hessian's pattern never changes; on a soft one garment vertices
/// slide onto other faces, the patterns change and each factorization reuses the
/// ordering of the one before, which the checkpoint has to carry for bit-identity.
class PatternOptimizerResume : public ::testing::TestWithParam<bool> {};

TEST_P(PatternOptimizerResume, ContinuesExactlyLikeAnUninterruptedRun) {
  test::SleeveSceneOptions scene_options;
  scene_options.soft_body = GetParam();
  PatternOptimizerOptions options;
  options.max_iterations = 6;
  VecX straight;
  CholeskyOrdering straight_ordering;
  {
    auto scene = test::make_sleeve_scene(scene_options);
    scene->sim->solve();
    DesignProblem problem(*scene->sim, target_objective(*scene->sim));
    PatternOptimizer optimizer(problem, options);
    optimizer.run();
    ASSERT_EQ(optimizer.history().size(), 7u);
    straight = problem.accepted_parameters();
    straight_ordering = problem.accepted_ordering();
  }
  const fs::path file = scratch("resume.json");
  std::vector<std::string> names;
  {
    auto scene = test::make_sleeve_scene(scene_options);
    scene->sim->solve();
    auto objective = target_objective(*scene->sim);
    names = term_names(*objective);
    DesignProblem problem(*scene->sim, objective);
    PatternOptimizerOptions first = options;
    first.max_iterations = 3;
    PatternOptimizer optimizer(problem, first);
    optimizer.run([&](const OptimizationIteration&) {
      write_checkpoint(file, optimizer.checkpoint(), names);
    });
  }
  auto scene = test::make_sleeve_scene(scene_options);
  scene->sim->solve();
  DesignProblem problem(*scene->sim, target_objective(*scene->sim));
  PatternOptimizer optimizer(problem, options);
  optimizer.resume(read_checkpoint(file, names));
  EXPECT_EQ(optimizer.history().size(), 4u);
  optimizer.run();
  ASSERT_EQ(optimizer.history().size(), 7u);
  EXPECT_EQ(problem.accepted_parameters(), straight);
  EXPECT_EQ(problem.accepted_ordering().permutation, straight_ordering.permutation);
  // The accepted point holds a factorization, made where the checkpoint says.
  ASSERT_TRUE(problem.accepted_held_point());
  EXPECT_TRUE(read_checkpoint(file, names).held_point);
  fs::remove_all(file.parent_path());
}

INSTANTIATE_TEST_SUITE_P(Body, PatternOptimizerResume, ::testing::Values(false, true),
                         [](const auto& param_info) {
                           return param_info.param ? "soft" : "rigid";
                         });

}  // namespace tightfit::pattern_optimizer_checkpoint_test
