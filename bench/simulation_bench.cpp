/// Forward simulation of a sleeve on a soft cylinder at three resolutions (~2k, 8k and
/// 32k garment triangles): per Newton iteration the assembly, factorization and solve
/// times, the total equilibrium time from a cold start (the initial embedding) and from
/// a warm start (the equilibrium, after a 1 % change of the rest shape), and the
/// nonzeros of the Hessian and of its Cholesky factor. The second argument picks the
/// solve: 1 the default (each factorization reused for Newton–Krylov chord steps), 0 plain
/// Newton (a factorization per step); the two run one after the other at each
/// resolution, so their ratio is of one run.
///
/// BM_SleeveFactorSolve: at the equilibrium, one application of the Hessian's
/// factorization in double precision (SparseCholesky::solve) and with the factor rounded
/// to single precision (solve_preconditioner, what the Krylov solves use), alternately,
/// each as a fraction of one numeric factorization of the same matrix.
#include <benchmark/benchmark.h>

#include "tightfit/body/body_builder.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {
namespace {

struct SleeveScene {
  Body body;
  std::unique_ptr<LimitSurface> surface;
  Garment garment;
};

SleeveScene make_scene(double garment_edge) {
  SleeveScene s;
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.3;
  cyl.edge_length = std::max(0.004, 2 * garment_edge);
  VolumeOptions volume = default_volume_options(cyl.edge_length);
  volume.core.soft_tissue = 0.02;
  s.body = cylinder_body(cyl, volume);
  s.surface = std::make_unique<LimitSurface>(s.body.surface);
  SleeveParams sp;
  sp.radius = cyl.radius;
  sp.axial_begin = -0.1;
  sp.axial_end = 0.1;
  sp.hoop_scale = 0.9;
  sp.axial_scale = 0.95;
  sp.edge_length = garment_edge;
  sp.pin_first_ring = sp.pin_last_ring = true;
  s.garment = make_sleeve(sp, *s.surface, s.body.surface.vertices);
  return s;
}

void report(benchmark::State& state, const SleeveScene& s, const NewtonReport& r) {
  double assembly = 0, factorization = 0, solve = 0;
  for (const auto& it : r.history) {
    assembly += it.seconds_assembly;
    factorization += it.seconds_factorization;
    solve += it.seconds_solve;
  }
  const double n = std::max<double>(1.0, static_cast<double>(r.history.size()));
  state.counters["garment_triangles"] =
      static_cast<double>(s.garment.topology->garment_triangles.rows());
  state.counters["body_tets"] = s.body.volume.num_tets();
  state.counters["newton_iterations"] = r.iterations;
  state.counters["chord_steps"] = r.chord_steps;
  state.counters["factorizations"] = r.factorizations;
  state.counters["assembly_s_per_it"] = assembly / n;
  state.counters["factorization_s_per_it"] = factorization / n;
  state.counters["solve_s_per_it"] = solve / n;
  state.counters["it_over_factorization"] =
      (assembly + factorization + solve) / std::max(factorization, 1e-12);
  state.counters["hessian_nnz"] = static_cast<double>(r.hessian_nonzeros);
  state.counters["factor_nnz"] = static_cast<double>(r.factor_nonzeros);
}

/// The solve the second argument asks for (see the file comment).
ChordSteps chords(const benchmark::State& state) {
  return state.range(1) != 0 ? ChordSteps{nullptr, true} : ChordSteps{};
}

void BM_SleeveColdStart(benchmark::State& state) {
  const SleeveScene s = make_scene(static_cast<double>(state.range(0)) * 1e-4);
  NewtonReport r;
  for (auto _ : state) {
    GarmentSimulation sim(s.body, *s.surface, s.garment, SimulationMaterials{});
    r = sim.solve(chords(state));
  }
  report(state, s, r);
}

void BM_SleeveWarmStart(benchmark::State& state) {
  const SleeveScene s = make_scene(static_cast<double>(state.range(0)) * 1e-4);
  GarmentSimulation sim(s.body, *s.surface, s.garment, SimulationMaterials{});
  sim.solve(chords(state));
  const Points2 rest = sim.garment().rest_positions();
  NewtonReport r;
  bool shrink = true;
  for (auto _ : state) {
    sim.set_rest_positions(rest * (shrink ? 0.99 : 1.0));
    shrink = !shrink;
    r = sim.solve(chords(state));
  }
  report(state, s, r);
}

void BM_SleeveFactorSolve(benchmark::State& state) {
  const SleeveScene s = make_scene(static_cast<double>(state.range(0)) * 1e-4);
  GarmentSimulation sim(s.body, *s.surface, s.garment, SimulationMaterials{});
  sim.solve();
  const SparseMatrix H = sim.problem().hessian();
  SparseCholesky cholesky;
  if (!cholesky.factorize(H)) {
    state.SkipWithError("the equilibrium Hessian is not positive definite");
    return;
  }
  const VecX b = sim.problem().gradient() + VecX::Ones(H.rows());
  double factorization = 0.0, exact = 0.0, single = 0.0;
  int rounds = 0;
  for (auto _ : state) {
    auto t0 = SteadyClock::now();
    cholesky.factorize(H);
    factorization += seconds_since(t0);
    // The first application rounds the new factor: left out of the timed ones.
    benchmark::DoNotOptimize(cholesky.solve_preconditioner(b));
    for (int k = 0; k < 20; ++k) {
      auto t1 = SteadyClock::now();
      benchmark::DoNotOptimize(cholesky.solve(b));
      exact += seconds_since(t1);
      t1 = SteadyClock::now();
      benchmark::DoNotOptimize(cholesky.solve_preconditioner(b));
      single += seconds_since(t1);
    }
    ++rounds;
  }
  const double solves = 20.0 * rounds;
  state.counters["factor_nnz"] = static_cast<double>(cholesky.factor_nonzeros());
  state.counters["factorization_ms"] = 1e3 * factorization / rounds;
  state.counters["solve_ms"] = 1e3 * exact / solves;
  state.counters["single_solve_ms"] = 1e3 * single / solves;
  state.counters["single_over_solve"] = single / exact;
  state.counters["solve_over_factorization"] = (exact / solves) / (factorization / rounds);
}

// Garment edge length in 0.1 mm: ~2k, 8k and 32k triangles on a 20 cm sleeve.
/// Both solves at each resolution, one after the other.
void alternate_solves(benchmark::internal::Benchmark* b) {
  for (int edge : {79, 40, 20})
    for (int reuse : {0, 1}) b->Args({edge, reuse});
}

BENCHMARK(BM_SleeveColdStart)->Apply(alternate_solves)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_SleeveWarmStart)->Apply(alternate_solves)->Unit(benchmark::kSecond)->Iterations(2);
BENCHMARK(BM_SleeveFactorSolve)->Arg(79)->Arg(40)->Arg(20)->Unit(benchmark::kSecond)->Iterations(5);

}  // namespace
}  // namespace tightfit

#include "bench_main.hpp"
