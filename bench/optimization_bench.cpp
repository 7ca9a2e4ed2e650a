/// Pattern optimization (L-BFGS with adjoint gradients): three example scenes of
/// examples/ (the Fig. 3b tapered cylinder, the pants stretch row of Table 1, the soft
/// sleeve), run exactly as `tightfit optimize` runs them, and two scenes at two
/// resolutions: (a) the stretch sleeve of examples/optimize_sleeve_stretch.json (rigid
/// cylinder, stretch objective in [1.02, 1.06], seam-length and spacing regularizers)
/// and (b) a sleeve on a soft Neo-Hookean cylinder with a shape objective towards a
/// tapered cylinder. Per accepted L-BFGS iteration (averaged over the run, the initial
/// evaluation excluded): wall time, forward Newton solves, objective evaluations and
/// gradient (term gradients + adjoint solve + pull-back), line-search trials, Newton
/// and chord steps, factorizations and GMRES iterations, from the optimizer's
/// per-iteration records; and one numeric Cholesky factorization of the equilibrium
/// Hessian at the final state (symbolic analysis done beforehand), with the ratio
/// iteration / factorization, and the other pieces of a Newton step there (gradient,
/// Hessian assembly, the factors of the Hessian operator, one product, one solve).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "tightfit/api/optimize.hpp"
#include "tightfit/body/body_builder.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/shape_objective.hpp"
#include "tightfit/objectives/stretch_objective.hpp"

namespace tightfit {
namespace {

struct Scene {
  Body body;
  std::unique_ptr<LimitSurface> surface;
  std::unique_ptr<GarmentSimulation> sim;
};

/// A sleeve 10 % short around and 5 % short along, |z| <= half_length, jittered
/// interior, both cuffs pinned.
SleeveParams jittered_sleeve(double radius, double half_length, double edge) {
  SleeveParams sp;
  sp.radius = radius;
  sp.axial_begin = -half_length;
  sp.axial_end = half_length;
  sp.hoop_scale = 0.9;
  sp.axial_scale = 0.95;
  sp.edge_length = edge;
  sp.jitter = 0.3;
  sp.pin_first_ring = sp.pin_last_ring = true;
  return sp;
}

/// (a): examples/optimize_sleeve_stretch.json with garment edge `edge` (m).
std::unique_ptr<Scene> stretch_scene(double edge) {
  auto s = std::make_unique<Scene>();
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.2;
  cyl.edge_length = std::min(0.01, edge);
  s->body.surface = cylinder_surface(cyl);
  s->body.volume.vertices = s->body.surface.vertices;
  s->body.volume.tets.resize(0, 4);
  s->surface = std::make_unique<LimitSurface>(s->body.surface);
  const SleeveParams sp = jittered_sleeve(cyl.radius, 0.05, edge);
  SimulationMaterials m;
  m.rigid_body = true;
  s->sim = std::make_unique<GarmentSimulation>(
      s->body, *s->surface, make_sleeve(sp, *s->surface, s->body.surface.vertices), m);
  return s;
}

/// (b): a sleeve on a soft cylinder (pinned core deeper than 20 mm), garment edge `edge`.
std::unique_ptr<Scene> soft_scene(double edge) {
  auto s = std::make_unique<Scene>();
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.3;
  cyl.edge_length = edge;
  VolumeOptions volume = default_volume_options(cyl.edge_length);
  volume.core.soft_tissue = 0.02;
  s->body = cylinder_body(cyl, volume);
  s->surface = std::make_unique<LimitSurface>(s->body.surface);
  const SleeveParams sp = jittered_sleeve(cyl.radius, 0.1, edge);
  SimulationMaterials m;
  m.body.youngs_modulus = 24780;
  m.body.poisson_ratio = 0.49;
  m.seam.youngs_modulus = 1e6;
  s->sim = std::make_unique<GarmentSimulation>(
      s->body, *s->surface, make_sleeve(sp, *s->surface, s->body.surface.vertices), m);
  return s;
}

/// Target of (b): a cylinder tapering from radius 49 mm to 46 mm along the sleeve.
ImlsSurface tapered_target() {
  const int rings = 61, around = 72;
  Points3 p(rings * around, 3), n(rings * around, 3);
  for (int i = 0; i < rings; ++i) {
    const double z = -0.15 + 0.3 * i / (rings - 1);
    const double r = 0.0475 - 0.015 * z;
    for (int j = 0; j < around; ++j) {
      const double a = 2.0 * std::numbers::pi * j / around;
      p.row(i * around + j) << r * std::cos(a), r * std::sin(a), z;
      n.row(i * around + j) << std::cos(a), std::sin(a), 0.0;
    }
  }
  return ImlsSurface(p, n, 0.01);
}

void report(benchmark::State& state, DesignProblem& problem, const PatternOptimizer& optimizer) {
  const auto& h = optimizer.history();
  double forward = 0, objective = 0, adjoint = 0, total = 0, assembly = 0, factor_time = 0;
  int newton = 0, trials = 0, chord = 0, factorizations = 0, krylov = 0;
  const int n = static_cast<int>(h.size()) - 1;
  for (int k = 1; k <= n; ++k) {
    forward += h[k].seconds_forward;
    objective += h[k].seconds_objective;
    adjoint += h[k].seconds_adjoint;
    assembly += h[k].seconds_assembly;
    factor_time += h[k].seconds_factorization;
    total += h[k].seconds - h[k - 1].seconds;
    newton += h[k].newton_iterations;
    chord += h[k].chord_steps;
    trials += h[k].line_search_trials;
    factorizations += h[k].factorizations;
    krylov += h[k].krylov_iterations;
  }
  GarmentSimulation& sim = problem.simulation();
  const SparseMatrix H = sim.problem().hessian();
  SparseCholesky cholesky;
  cholesky.factorize(H);  // symbolic analysis + numeric
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = cholesky.factorize(H);
  const double factorization =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The pieces of a Newton step at the final state (s, the fastest of three runs).
  auto seconds_of = [](auto&& fn) {
    double best = std::numeric_limits<double>::infinity();
    for (int run = 0; run < 3; ++run) {
      const auto start = std::chrono::steady_clock::now();
      fn();
      best = std::min(
          best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return best;
  };
  NewtonProblem& equilibrium = sim.problem();
  VecX g;
  const double gradient_s = seconds_of([&] { g = equilibrium.gradient(); });
  const double hessian_s = seconds_of([&] { benchmark::DoNotOptimize(equilibrium.hessian()); });
  std::optional<LinearOperator> product;
  const double operator_s = seconds_of([&] { product = equilibrium.hessian_operator(); });
  const double product_s = seconds_of([&] { benchmark::DoNotOptimize((*product)(g)); });
  const double solve_s = seconds_of([&] { benchmark::DoNotOptimize(cholesky.solve(g)); });
  state.counters["gradient_s"] = gradient_s;
  state.counters["hessian_s"] = hessian_s;
  state.counters["hessian_operator_s"] = operator_s;
  state.counters["product_s"] = product_s;
  state.counters["solve_s"] = solve_s;
  const double d = std::max(1, n);
  state.counters["threads"] = thread_count();
  state.counters["garment_triangles"] =
      static_cast<double>(sim.garment().topology->garment_triangles.rows());
  state.counters["body_tets"] = static_cast<double>(sim.body().volume.num_tets());
  state.counters["dofs"] = static_cast<double>(sim.problem().num_dofs());
  state.counters["parameters"] = problem.num_parameters();
  state.counters["lbfgs_iterations"] = n;
  state.counters["trials_per_it"] = trials / d;
  state.counters["newton_per_it"] = newton / d;
  state.counters["chord_per_it"] = chord / d;
  state.counters["factorizations_per_it"] = factorizations / d;
  state.counters["gmres_per_it"] = krylov / d;
  state.counters["it_s"] = total / d;
  state.counters["forward_s_per_it"] = forward / d;
  state.counters["assembly_s_per_it"] = assembly / d;
  state.counters["newton_factorization_s_per_it"] = factor_time / d;
  state.counters["objective_s_per_it"] = objective / d;
  state.counters["adjoint_s_per_it"] = adjoint / d;
  state.counters["factorization_s"] = factorization;
  state.counters["factorization_ok"] = ok ? 1 : 0;
  state.counters["it_over_factorization"] = total / d / std::max(factorization, 1e-12);
  state.counters["hessian_nnz"] = static_cast<double>(H.nonZeros());
  state.counters["factor_nnz"] = static_cast<double>(cholesky.factor_nonzeros());
  state.counters["objective_ratio"] = h.back().value / h.front().value;
}

/// Optimizes an example scene (examples/NAME.json, objective and options exactly as
/// `tightfit optimize` builds them: the public API) for `iterations` L-BFGS iterations.
void optimize_example(benchmark::State& state, const std::string& name, int iterations) {
  for (auto _ : state) {
    api::Scene scene =
        api::Scene::read(std::string(TIGHTFIT_SOURCE_DIR) + "/examples/" + name + ".json");
    api::OptimizeOptions options;
    options.max_iterations = iterations;
    api::Optimization optimization(scene, options);
    optimization.run();
    report(state, optimization.problem(), optimization.optimizer());
  }
}

void BM_OptimizeExampleTaperedCylinder(benchmark::State& state) {
  optimize_example(state, "optimize_cylinder_tapered", static_cast<int>(state.range(0)));
}
void BM_OptimizeExamplePantsStretch(benchmark::State& state) {
  optimize_example(state, "optimize_pants_stretch", static_cast<int>(state.range(0)));
}
void BM_OptimizeExampleSoftSleeve(benchmark::State& state) {
  optimize_example(state, "optimize_sleeve_soft", static_cast<int>(state.range(0)));
}

void BM_OptimizeStretchSleeve(benchmark::State& state) {
  for (auto _ : state) {
    auto scene = stretch_scene(static_cast<double>(state.range(0)) * 1e-4);
    GarmentSimulation& sim = *scene->sim;
    auto objective = std::make_shared<DesignTermSum>();
    objective->add(std::make_shared<StretchObjective>(sim.garment(), StretchBounds{1.02, 1.06}),
                   1.0);
    objective->add(
        std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(sim.garment())), 1.0);
    objective->add(
        std::make_shared<EdgeLengthDifferenceTerm>(even_spacing_regularizer(sim.garment())), 0.1);
    DesignProblem problem(sim, objective);
    PatternOptimizerOptions o;
    o.max_iterations = static_cast<int>(state.range(1));
    PatternOptimizer optimizer(problem, o);
    optimizer.run();
    report(state, problem, optimizer);
  }
}

void BM_OptimizeSoftSleeveShape(benchmark::State& state) {
  for (auto _ : state) {
    auto scene = soft_scene(static_cast<double>(state.range(0)) * 1e-4);
    GarmentSimulation& sim = *scene->sim;
    auto objective = std::make_shared<DesignTermSum>();
    objective->add(
        std::make_shared<ShapeObjective>(tapered_target(), sim.garment().num_garment_vertices()),
        1.0);
    objective->add(
        std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(sim.garment())), 1.0);
    DesignProblem problem(sim, objective);
    PatternOptimizerOptions o;
    o.max_iterations = static_cast<int>(state.range(1));
    PatternOptimizer optimizer(problem, o);
    optimizer.run();
    report(state, problem, optimizer);
  }
}

// Args: garment edge length in 0.1 mm, L-BFGS iterations.
BENCHMARK(BM_OptimizeStretchSleeve)
    ->Args({120, 10})
    ->Args({60, 10})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_OptimizeSoftSleeveShape)
    ->Args({140, 5})
    ->Args({100, 5})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
// Arg: L-BFGS iterations.
BENCHMARK(BM_OptimizeExampleTaperedCylinder)->Arg(20)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_OptimizeExamplePantsStretch)->Arg(10)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_OptimizeExampleSoftSleeve)->Arg(10)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace tightfit

#include "bench_main.hpp"
