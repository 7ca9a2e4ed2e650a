#pragma once
/// The main() of the benchmarks: the allocator set up as tightfit's CLI sets it up
/// (common/memory_reuse.hpp), then Google Benchmark.
#include <benchmark/benchmark.h>

#include "tightfit/common/memory_reuse.hpp"

int main(int argc, char** argv) {
  tightfit::keep_freed_memory_for_reuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
