#pragma once
/// tightfit's public C++ API: everything a front-end needs to load a scene, simulate
/// the garment on the body, optimize its pattern and write the outputs, in one include.
/// docs/api.md is the guide; examples/api/minimal.cpp a complete program.
///
///   tightfit::api::Scene scene = tightfit::api::Scene::read("scene.json");
///   const tightfit::api::SimulationRun run = tightfit::api::simulate(scene);
///   tightfit::api::write_simulation_outputs(scene, run, "out");
///
/// Errors are exceptions (common/error.hpp): InputError for bad input (its source()
/// names the file, its message the JSON path), SolverError when a solve fails,
/// std::exception otherwise. Units are SI (m, Pa, N, J, s) throughout.
#include "tightfit/api/optimize.hpp"     // IWYU pragma: export
#include "tightfit/api/run_outputs.hpp"  // IWYU pragma: export
#include "tightfit/api/scene.hpp"        // IWYU pragma: export
#include "tightfit/api/simulate.hpp"     // IWYU pragma: export
#include "tightfit/common/error.hpp"     // IWYU pragma: export
