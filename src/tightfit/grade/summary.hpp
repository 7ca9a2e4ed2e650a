#pragma once
/// What `tightfit grade` gathers from its bodies' folders into grade.json: per body its
/// status (and error), the objective before and after, iterations, the wall time split
/// into stages, stretch and pressure statistics and the seam lengths of its pattern; per
/// seam its length on every size and the change from the size before.
///
/// grade.json: {"format": "tightfit-grade", "version": 1, "design", "bodies_file",
///   "date", "counts": {"bodies", "done", "failed", "not_run"},
///   "bodies": [{"name", "status": "done" | "failed" | "running" | "not_run", "folder",
///     "error" (failed), "objective": {"initial", "final", "ratio"}, "iterations",
///     "stop_reason", "seconds": {"body", "layout", "initial_solve", "iterations",
///     "total"}, "stretch_max", "stretch_min", "pressure_mmhg" ({"min", "median",
///     "max"}, area-weighted), "pressure_spread", "lift_off_share",
///     "pieces": [{"name", "pressure_mmhg"}],
///     "seams_mm": {SEAM: {"a", "b", "mismatch"}}}],
///   "seams": [{"name", "length_mm": {BODY: mean of the two sides},   (pattern order)
///              "change_mm": {BODY: change from the graded body listed before it}}]}
/// "running": a status file says the body started and has not ended (killed, or still
/// running); "not_run": no status file. counts/not_run counts both.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/grade/bodies.hpp"

namespace tightfit {

/// Folder of body `name` in grading folder `dir`: dir/bodies/name.
std::filesystem::path grade_body_folder(const std::filesystem::path& dir, const std::string& name);

struct GradedBody {
  std::string name;
  std::string status;              ///< as in grade.json
  std::string error;               ///< failed bodies
  nlohmann::json entry;            ///< its grade.json entry
  std::optional<Pattern> pattern;  ///< done bodies: the optimized pattern (pieces.json)
};

struct GradeSummary {
  std::vector<GradedBody> bodies;  ///< in the bodies file's order
  nlohmann::json json;             ///< grade.json
  int not_done = 0;                ///< bodies whose status is not "done"
};

/// Reads every body's folder in `dir`. A done body whose result files cannot be read is
/// reported failed with the reader's error.
GradeSummary gather_grade(const std::vector<GradeBody>& bodies, const std::filesystem::path& dir,
                          const std::string& design_file, const std::string& bodies_file);

}  // namespace tightfit
