#pragma once
/// `--keep-failed DIR2` of `simulate` and `optimize`: a forward solve that does not
/// converge leaves its last state in DIR2 — the fit outputs at that state and per-vertex
/// maps of the unbalanced force — so that the user can see which part of the layout is
/// at fault. The folder is a run folder (`tightfit export` reads it).
#include <filesystem>
#include <string>
#include <vector>

#include "tightfit/scene/loader.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::app {

/// Throws InputError when `keep_failed` (non-empty) names the same folder as `out_dir`.
void check_keep_failed_folder(const std::string& keep_failed, const std::string& out_dir);

/// Writes the simulation's current (failed) state into `dir`: report.html, garment.ply,
/// result.json with "newton": {"converged": false, "message", residual, tolerance} and
/// "failure" (where the largest force acts, largest garment and body residuals, N),
/// state.json, …, and garment_residual.ply / body_residual.ply with the unbalanced force
/// per vertex (N). Returns the files written.
std::vector<std::string> keep_failed_state(const std::filesystem::path& dir, bool force,
                                           const std::string& scene_file, const LoadedScene& scene,
                                           GarmentSimulation& sim, const std::string& message);

/// keep_failed_state into `keep_failed`, then prints the files and what they hold.
void report_kept_failure(const std::string& keep_failed, bool force, const std::string& scene_file,
                         const LoadedScene& scene, GarmentSimulation& sim,
                         const std::string& message);

}  // namespace tightfit::app
