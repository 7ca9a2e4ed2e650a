/// The cost of a measured knit (physics/fabric_law.hpp) against the isotropic relaxed
/// StVK fabric on the same scene: a sleeve on a soft cylinder (~8k garment triangles,
/// both end rings pinned) designed for a pressure range. Two design problems, one per
/// fabric, of similar stiffness (the knit's curves are straight lines at the plane-stress
/// stiffness E t / (1 − ν²), coupling ν, shear E t / (2 (1 + ν))), are solved cold, then
/// evaluated alternately — one design iteration each: a warm-started forward solve after
/// a boundary step of 2 % of the boundary edge and the adjoint gradient — so that the
/// ratio measured / isotropic is of one run on one machine state.
///
/// Counters: per fabric the seconds per design iteration, of them the assembly
/// (gradients and Hessians), and the Newton steps; `iteration_ratio` and
/// `assembly_ratio` (measured over isotropic).
#include <benchmark/benchmark.h>

#include "tightfit/body/body_builder.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/objectives/pressure_objective.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {
namespace {

struct Scene {
  Body body;
  std::unique_ptr<LimitSurface> surface;
  Garment garment;
};

Scene make_scene() {
  Scene s;
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.3;
  cyl.edge_length = 0.008;
  VolumeOptions volume = default_volume_options(cyl.edge_length);
  volume.core.soft_tissue = 0.02;
  s.body = cylinder_body(cyl, volume);
  s.surface = std::make_unique<LimitSurface>(s.body.surface);
  SleeveParams sp;
  sp.radius = cyl.radius;
  sp.axial_begin = -0.1;
  sp.axial_end = 0.1;
  sp.hoop_scale = 0.85;
  sp.axial_scale = 0.95;
  sp.edge_length = 0.004;
  sp.pin_first_ring = sp.pin_last_ring = true;
  s.garment = make_sleeve(sp, *s.surface, s.body.surface.vertices);
  return s;
}

/// A knit of straight strip curves as stiff as the isotropic default.
ClothMaterial equivalent_knit(const ClothMaterial& iso) {
  const double nu = iso.poisson_ratio;
  const double k = iso.youngs_modulus * iso.thickness / (1.0 - nu * nu);
  ClothMaterial m = iso;
  m.measured = std::make_shared<MeasuredFabric>(MeasuredFabric{
      "straight knit", FabricCurve({0.0, 1.0}, {0.0, k}), FabricCurve({0.0, 1.0}, {0.0, k}),
      std::nullopt, std::nullopt, nu, iso.youngs_modulus * iso.thickness / (2.0 * (1.0 + nu))});
  return m;
}

struct Run {
  std::unique_ptr<GarmentSimulation> sim;
  std::unique_ptr<DesignProblem> problem;
  double seconds = 0.0, assembly = 0.0;
  int newton = 0, iterations = 0;
};

Run make_run(const Scene& s, const ClothMaterial& fabric) {
  Run r;
  SimulationMaterials materials;
  materials.fabric = fabric;
  r.sim = std::make_unique<GarmentSimulation>(s.body, *s.surface, s.garment, materials);
  r.sim->solve();
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(std::make_shared<PressureObjective>(r.sim->garment(), fabric, 2000.0, 2600.0),
                 1.0);
  r.problem = std::make_unique<DesignProblem>(*r.sim, objective);
  return r;
}

void BM_MeasuredAgainstIsotropicDesignIteration(benchmark::State& state) {
  const Scene s = make_scene();
  const ClothMaterial iso;
  Run runs[2] = {make_run(s, iso), make_run(s, equivalent_knit(iso))};
  VecX direction = VecX::Zero(runs[0].problem->num_parameters());
  for (Eigen::Index k = 0; k < direction.size(); ++k) direction[k] = (k % 3 == 0) ? 1.0 : -0.5;
  direction.normalize();
  int round = 0;
  for (auto _ : state) {
    for (Run& r : runs) {
      const VecX p = r.problem->initial_parameters() +
                     (round % 2 == 0 ? 0.02 : -0.02) * r.problem->mean_boundary_edge() *
                         std::sqrt(static_cast<double>(direction.size())) * direction;
      const auto t0 = SteadyClock::now();
      const DesignEvaluation e = r.problem->evaluate(p, true);
      r.seconds += seconds_since(t0);
      if (!e.ok) {
        state.SkipWithError(("a design evaluation failed: " + e.failure).c_str());
        return;
      }
      r.assembly += e.seconds_assembly;
      r.newton += e.newton_iterations;
      ++r.iterations;
    }
    ++round;
  }
  const char* names[2] = {"isotropic", "measured"};
  for (int k = 0; k < 2; ++k) {
    const double n = std::max(1, runs[k].iterations);
    state.counters[std::string(names[k]) + "_s_per_it"] = runs[k].seconds / n;
    state.counters[std::string(names[k]) + "_assembly_s_per_it"] = runs[k].assembly / n;
    state.counters[std::string(names[k]) + "_newton_per_it"] = runs[k].newton / n;
  }
  state.counters["garment_triangles"] =
      static_cast<double>(s.garment.topology->garment_triangles.rows());
  state.counters["iteration_ratio"] = runs[1].seconds / runs[0].seconds;
  state.counters["assembly_ratio"] = runs[1].assembly / std::max(runs[0].assembly, 1e-12);
}

BENCHMARK(BM_MeasuredAgainstIsotropicDesignIteration)->Unit(benchmark::kSecond)->Iterations(6);

}  // namespace
}  // namespace tightfit

#include "bench_main.hpp"
