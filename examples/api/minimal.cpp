/// A minimal program on tightfit's public API (docs/api.md): loads a scene, simulates
/// the garment on the body and writes the outputs; a scene with an "optimize" section is
/// optimized instead, with a progress line per iteration and a callback that stops the
/// run after MAX_ITERATIONS iterations.
///
///   tightfit_api_minimal SCENE OUT_DIR [MAX_ITERATIONS]
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "tightfit/api/tightfit.hpp"

namespace {

namespace api = tightfit::api;

int simulate(api::Scene& scene, const std::filesystem::path& out) {
  const api::SimulationRun run = api::simulate(scene);
  std::printf("equilibrium after %d Newton iterations, force residual %.3g N\n",
              run.newton.iterations, run.newton.final_force_norm);
  const api::WrittenOutputs written = api::write_simulation_outputs(scene, run, out);
  const auto& pressure = written.result["fit"]["pressure_mmhg"];
  std::printf("pressure: median %.2f mmHg, max %.2f mmHg\n", pressure["median"].get<double>(),
              pressure["max"].get<double>());
  std::printf("%zu files in %s\n", written.files.size(), out.c_str());
  return 0;
}

int optimize(api::Scene& scene, const std::filesystem::path& out, int max_iterations) {
  api::Optimization optimization(scene);
  std::printf("%d design parameters, %zu objective terms\n", optimization.num_parameters(),
              optimization.term_names().size());
  const tightfit::OptimizationResult result =
      optimization.run([&](const tightfit::OptimizationIteration& it) {
        std::printf("iteration %d: objective %.6g\n", it.iteration, it.value);
        return it.iteration < max_iterations;  // false: stop after this one
      });
  std::printf("stopped: %s\n", result.stop_reason.c_str());
  const api::WrittenOutputs written = api::write_optimization_outputs(optimization, result, out);
  std::printf("%zu files in %s\n", written.files.size(), out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s SCENE OUT_DIR [MAX_ITERATIONS]\n", argv[0]);
    return 2;
  }
  try {
    api::Scene scene = api::Scene::read(argv[1]);
    const std::filesystem::path out = argv[2];
    std::filesystem::create_directories(out);
    if (scene.has_optimization()) return optimize(scene, out, argc == 4 ? std::stoi(argv[3]) : 5);
    return simulate(scene, out);
  } catch (const tightfit::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
