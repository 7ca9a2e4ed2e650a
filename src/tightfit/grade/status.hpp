#pragma once
/// The state of one body of a grading, DIR/bodies/NAME/grade_body.json (written
/// atomically): {"format": "tightfit-grade-body", "version": 1, "name", "status",
/// "fingerprint", "error" (failed bodies), "seconds" (wall time of the invocation that
/// finished it), "date"}. "running" is written before the optimization starts, "done"
/// or "failed" when it ends; a body left "running" was killed and resumes.
#include <filesystem>
#include <optional>
#include <string>

namespace tightfit {

/// Name of the status file in a body's folder.
inline constexpr const char* kGradeBodyFile = "grade_body.json";

struct GradeBodyStatus {
  std::string name;
  std::string status;       ///< "running", "done" or "failed"
  std::string fingerprint;  ///< grade/scene.hpp grade_fingerprint of the body's inputs
  std::string error;        ///< why it failed
  double seconds = 0.0;     ///< wall time (s) of the invocation that wrote the status
};

/// Writes `status` to `file` atomically.
void write_grade_body_status(const std::filesystem::path& file, const GradeBodyStatus& status);

/// The status in `file`; nullopt when there is none or it is not a grade status file.
std::optional<GradeBodyStatus> read_grade_body_status(const std::filesystem::path& file);

}  // namespace tightfit
