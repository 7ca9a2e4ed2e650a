#pragma once
/// The static equilibrium of a scene's garment on its body (what `tightfit simulate`
/// computes) and its output files: a thin layer over GarmentSimulation::solve and
/// ::analyze (solve/garment_simulation.hpp) and write_fit_run_outputs (api/run_outputs.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tightfit/api/scene.hpp"
#include "tightfit/solve/newton_solver.hpp"

namespace tightfit::api {

struct SimulateOptions {
  /// Newton's progress, one call per accepted step (empty: none).
  NewtonStepCallback on_newton_step;
};

/// What a simulation computed.
struct SimulationRun {
  NewtonReport newton;  ///< the solve (converged: the equilibrium was reached)
  FitAnalysis fit;      ///< stretch, tension and pressure at the equilibrium
  double seconds_solve = 0.0;
  double seconds_analysis = 0.0;
};

/// Solves for the equilibrium of the scene's garment on its body (loading the scene
/// first when needed) and analyzes the fit; the scene's simulation is left at the
/// equilibrium. Throws SolverError when Newton does not converge; the simulation then
/// holds the last accepted state (what `tightfit simulate --keep-failed` writes out).
SimulationRun simulate(Scene& scene, const SimulateOptions& options = {});

/// The files written and the run's summary (result.json).
struct WrittenOutputs {
  std::vector<std::string> files;  ///< names, in the order written
  nlohmann::json result;           ///< result.json as written
};

/// Writes the outputs of `run`, the simulation of `scene` that simulate() made, into
/// `folder` (which must exist): garment.ply, body.ply, the pattern files, result.json,
/// scene.json, state.json (for `tightfit export`), report.html and fit.glb
/// (write_fit_run_outputs). Each file is written atomically; for all of them or none,
/// write into common/output_directory.hpp's OutputDirectory::staging() and commit.
WrittenOutputs write_simulation_outputs(Scene& scene, const SimulationRun& run,
                                        const std::filesystem::path& folder);

}  // namespace tightfit::api
