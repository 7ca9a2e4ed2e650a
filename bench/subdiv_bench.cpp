// Limit-surface throughput on a real body mesh (data/bodies/mh_legs_male.obj, 7672
// triangles): stencils with second derivatives on regular and irregular faces,
// positions, walks, and closest-point projection with and without a hint.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/subdiv/limit_projector.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {
namespace {

struct Fixture {
  TriMesh mesh;
  std::unique_ptr<LimitSurface> surface;
  std::unique_ptr<LimitProjector> projector;
  std::vector<SurfacePoint> regular, irregular, all;
  std::vector<Vec3> targets;  // points near the surface and their exact projections' sources
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    x.mesh = read_obj(std::string(TIGHTFIT_DATA_DIR) + "/bodies/mh_legs_male.obj");
    x.surface = std::make_unique<LimitSurface>(x.mesh);
    x.projector = std::make_unique<LimitProjector>(*x.surface, x.mesh.vertices);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> face(0, x.surface->num_faces() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0), offset(-2e-3, 2e-3);
    while (x.regular.size() < 4096 || x.irregular.size() < 4096) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const SurfacePoint s{face(rng), u, v};
      auto& list = x.surface->is_irregular(s.face) ? x.irregular : x.regular;
      if (list.size() < 4096) list.push_back(s);
      x.all.push_back(s);
    }
    for (std::size_t k = 0; k < 4096; ++k) {
      const SurfacePoint& s = x.all[k];
      x.targets.push_back(x.surface->position(s, x.mesh.vertices) +
                          offset(rng) * x.surface->normal(s, x.mesh.vertices));
    }
    return x;
  }();
  return f;
}

void weights(benchmark::State& state, const std::vector<SurfacePoint>& points) {
  const Fixture& f = fixture();
  LimitWeights w;
  std::size_t k = 0;
  for (auto _ : state) {
    f.surface->weights(points[k++ & 4095], w);
    benchmark::DoNotOptimize(w.dvv.data());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_WeightsRegularFaces(benchmark::State& state) { weights(state, fixture().regular); }
void BM_WeightsIrregularFaces(benchmark::State& state) { weights(state, fixture().irregular); }
BENCHMARK(BM_WeightsRegularFaces);
BENCHMARK(BM_WeightsIrregularFaces);

void BM_EvaluateFrame(benchmark::State& state) {
  const Fixture& f = fixture();
  std::size_t k = 0;
  for (auto _ : state) {
    const LimitFrame fr = f.surface->evaluate(f.all[k++ & 4095], f.mesh.vertices);
    benchmark::DoNotOptimize(fr.xvv.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EvaluateFrame);

void BM_Walk(benchmark::State& state) {
  const Fixture& f = fixture();
  std::size_t k = 0;
  for (auto _ : state) {
    const LimitSurface::Walk w =
        f.surface->walk(f.all[k & 4095], Vec2(0.7, -0.4 + 0.0001 * (k & 255)));
    ++k;
    benchmark::DoNotOptimize(w.end.u);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Walk);

void BM_ProjectWithKdTree(benchmark::State& state) {
  const Fixture& f = fixture();
  std::size_t k = 0;
  for (auto _ : state) {
    const SurfacePoint s = f.projector->project(f.targets[k++ & 4095]);
    benchmark::DoNotOptimize(s.u);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProjectWithKdTree);

void BM_ProjectFromNearbyHint(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<SurfacePoint> hints;
  for (std::size_t k = 0; k < 4096; ++k)
    hints.push_back(f.surface->walk(f.all[k], Vec2(0.05, 0.03)).end);
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t i = k++ & 4095;
    const SurfacePoint s = f.surface->project(f.targets[i], f.mesh.vertices, hints[i]);
    benchmark::DoNotOptimize(s.u);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProjectFromNearbyHint);

void BM_ProjectThroughSurfaceCache(benchmark::State& state) {
  const Fixture& f = fixture();
  std::size_t k = 0;
  for (auto _ : state) {
    const SurfacePoint s = f.surface->project(f.targets[k++ & 4095], f.mesh.vertices);
    benchmark::DoNotOptimize(s.u);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProjectThroughSurfaceCache);

void BM_Construction(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    const LimitSurface s(f.mesh);
    benchmark::DoNotOptimize(s.num_faces());
  }
}
BENCHMARK(BM_Construction)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tightfit

#include "bench_main.hpp"
