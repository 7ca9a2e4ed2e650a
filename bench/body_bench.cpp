// Building the male legs body (read, validate, remesh, tetrahedralize, pin the core) at
// 15 mm and 10 mm edge length: wall time, tet counts and peak memory.
//
// Peak memory is getrusage's ru_maxrss, the peak of the whole process so far: run one
// size per process for a clean number, e.g.
//   body_bench --benchmark_filter='LegsBody/15'
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "tightfit/body/body_spec.hpp"

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void LegsBody(benchmark::State& state) {
  const double edge = static_cast<double>(state.range(0)) * 1e-3;
  const tightfit::BodySpec spec = tightfit::parse_body_spec(
      nlohmann::json{{"mesh", TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj"}, {"edge_length", edge}}, "", ".",
      "bench");
  tightfit::Body body;
  tightfit::BuildReport report;
  for (auto _ : state) {
    report = tightfit::BuildReport();
    body = tightfit::build_body(spec, &report);
    benchmark::DoNotOptimize(body.volume.tets.data());
  }
  state.counters["surface_vertices"] = body.num_surface_vertices();
  state.counters["volume_vertices"] = body.num_vertices();
  state.counters["tets"] = body.volume.num_tets();
  state.counters["pinned"] = static_cast<double>(body.pinned.size());
  for (const auto& [stage, seconds] : report.stage_seconds) state.counters[stage + "_s"] = seconds;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

BENCHMARK(LegsBody)->Arg(15)->Arg(10)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace

#include "bench_main.hpp"
