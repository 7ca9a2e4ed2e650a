/// Poses: what a pose costs next to a forward solve, on the sliding pants
/// of examples/optimize_pants_sliding.json (the legs body, four stride poses). At the
/// neutral equilibrium of the initial pattern:
///  * PoseBody: skinning one pose of the body (weights transferred beforehand);
///  * SlidingValue / SlidingGradient: the sliding objective of one pose, its value and
///    its value with every partial derivative (Xbar, s, y);
///  * AdjointGradient/stretch and /stretch+sliding4: the whole design gradient (terms,
///    adjoint solve, pull-back) of the example's objective without and with the sliding
///    term over four poses — the per-iteration overhead of the poses, since the forward
///    solves are the same;
///  * ForwardSolve: the Newton solve of the neutral pose from the embedded initial state.
#include <benchmark/benchmark.h>

#include "bench_main.hpp"
#include "tightfit/body/posed_body.hpp"
#include "tightfit/body/skin_transfer.hpp"
#include "tightfit/design/adjoint_gradient.hpp"
#include "tightfit/objectives/sliding_objective.hpp"
#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/optimization_setup.hpp"

namespace tightfit {
namespace {

struct PoseScene {
  OptimizationScene spec;
  std::unique_ptr<LoadedScene> scene;
  std::unique_ptr<GarmentSimulation> sim;
  EmbeddedState initial;
  PointWeights weights;
  std::vector<PoseMotions> poses;
};

PoseScene& pose_scene() {
  static PoseScene s = [] {
    PoseScene p;
    p.spec = read_optimization_scene(TIGHTFIT_SOURCE_DIR "/examples/optimize_pants_sliding.json");
    p.scene = load_scene(p.spec.scene);
    p.sim = make_simulation(*p.scene);
    p.initial = p.sim->problem().state();
    p.sim->solve();
    p.weights = body_skin_weights(p.scene->body, p.spec.scene.rig->weights);
    for (const auto& [name, bones] : p.spec.optimization.poses.bone_motions)
      p.poses.push_back({name, pose_body(p.scene->body, p.scene->body.volume.vertices, p.weights,
                                         bones, p.spec.optimization.poses.skinning)
                                   .motions});
    return p;
  }();
  return s;
}

void PoseBody(benchmark::State& state) {
  PoseScene& p = pose_scene();
  const auto& bones = p.spec.optimization.poses.bone_motions.front().second;
  for (auto _ : state)
    benchmark::DoNotOptimize(pose_body(p.scene->body, p.sim->body_positions(), p.weights, bones,
                                       p.spec.optimization.poses.skinning));
}

void SlidingValue(benchmark::State& state) {
  PoseScene& p = pose_scene();
  const SlidingObjective term(p.sim->garment(), p.sim->materials(), p.sim->surface(),
                              p.scene->body.num_vertices(), {p.poses.front()}, 0.3);
  const SimulationDesignState ds(*p.sim);
  for (auto _ : state) benchmark::DoNotOptimize(term.value(ds.view()));
}

void SlidingGradient(benchmark::State& state) {
  PoseScene& p = pose_scene();
  const SlidingObjective term(p.sim->garment(), p.sim->materials(), p.sim->surface(),
                              p.scene->body.num_vertices(), {p.poses.front()}, 0.3);
  const SimulationDesignState ds(*p.sim);
  VecX dx(ds.x.size()), dr(2 * ds.rest.rows()),
      dsv(2 * static_cast<Eigen::Index>(ds.garment.size())), dy(ds.body.size());
  for (auto _ : state) {
    dx.setZero();
    dr.setZero();
    dsv.setZero();
    dy.setZero();
    benchmark::DoNotOptimize(term.value(ds.view()));
    term.add_gradient(ds.view(), dx, dr);
    term.add_embedding_gradient(ds.view(), dsv, dy);
  }
}

void AdjointGradient(benchmark::State& state) {
  PoseScene& p = pose_scene();
  OptimizationSpec spec = p.spec.optimization;
  if (state.range(0) == 0) spec.sliding.reset();
  const auto objective = build_objective(spec, *p.sim);
  AdjointSolver solver;
  for (auto _ : state) benchmark::DoNotOptimize(solver.rest_gradient(*p.sim, *objective));
  state.SetLabel(state.range(0) == 0 ? "stretch" : "stretch+sliding4");
}

void ForwardSolve(benchmark::State& state) {
  PoseScene& p = pose_scene();
  for (auto _ : state) {
    p.sim->set_state(p.initial);
    benchmark::DoNotOptimize(p.sim->solve());
  }
}

BENCHMARK(PoseBody)->Unit(benchmark::kMillisecond);
BENCHMARK(SlidingValue)->Unit(benchmark::kMillisecond);
BENCHMARK(SlidingGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(AdjointGradient)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(ForwardSolve)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace tightfit
