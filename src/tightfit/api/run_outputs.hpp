#pragma once
/// The output files of a run, written the same way by the command that ran it
/// (`simulate`, `optimize`, `layout`), by `tightfit export`, which regenerates them from
/// the run's state.json (scene/run_state.hpp), and by the public API (api/tightfit.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/run_state.hpp"
#include "tightfit/solve/garment_simulation.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit::api {

/// Garments with more pieces than this (covers: one piece per triangle) get no pattern
/// files: there is nothing to cut.
constexpr size_t kMaxPatternPieces = kMaxReportedPieces;

/// Writes the outputs of a run that ended at an equilibrium into `folder`, in this
/// order (each file atomically; the report comes last because it needs the viewer's
/// npm packages and its failure must not cost the rest): garment.ply, body.ply, the
/// pattern files, garment_pose_NAME.ply per pose of the scene (report/pose_outputs.hpp),
/// result.json (`state.result` with "fit" set to the fit statistics and "poses" to the
/// per-pose statistics when the scene has poses),
/// scene.json, history.json (optimize runs), state.json, report.html (with the
/// objective history of optimize runs), fit.glb. `state` is the run's state with the
/// simulation's pattern and equilibrium; its result gets the "fit" member.
/// `initial_pattern` (optimize runs: the scene's pattern before the optimization) gives
/// the report's before/after overlay; pieces are matched by name. The report is titled
/// and headed by its run summary (report_summary). Returns the names of the files
/// written.
std::vector<std::string> write_fit_run_outputs(const std::filesystem::path& folder,
                                               const GarmentSimulation& sim, const FitAnalysis& fit,
                                               ShapeOperatorKind pressure_operator, RunState& state,
                                               const Pattern* initial_pattern = nullptr);

/// Marks iteration `best` of a history.json document: "best_iteration" at the top and
/// "best": true on its record.
void mark_best_iteration(nlohmann::json& history, int best);

/// result.json's "run": {"command", "version", "date" (UTC, ISO 8601)}.
nlohmann::json run_identity_json(const std::string& command);

/// The report's run summary from a fit run's state (command, scene, version, date and,
/// from its result: status, stop reason, iterations, seconds, force residual,
/// objective before and after).
nlohmann::json report_summary(const RunState& state);

/// Writes the outputs of a layout run into `folder`: the pattern files of `garment`,
/// garment_embedded.ply (each garment vertex at its limit-surface point over the
/// control points `control`, n×3 m), layout.json (`state.result`) and state.json.
/// Returns the names of the files written.
std::vector<std::string> write_layout_run_outputs(const std::filesystem::path& folder,
                                                  const Garment& garment,
                                                  const LimitSurface& surface,
                                                  const Points3& control, const RunState& state);

/// What the run computed on, for result.json's "compute": {"threads": N, "blas":
/// {"name", "library", "config", "threads"}} (common/parallel.hpp).
nlohmann::json compute_json();

}  // namespace tightfit::api
