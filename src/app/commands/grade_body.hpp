#pragma once
/// One body of `tightfit grade`: one idempotent invocation that any batch engine (GNU
/// parallel, a Slurm array task, `grade --jobs`) can run, kill and run again.
///
/// DIR/bodies/NAME/ belongs to tightfit grade. It holds scene.json (the design scene
/// with this body's mesh and rig, paths relative to the folder, so that `tightfit
/// optimize DIR/bodies/NAME/scene.json` reproduces the run), grade_body.json (the status,
/// grade/status.hpp) and, once the body is done, the outputs of `tightfit optimize`.
///  * A body whose status is "done" for the same inputs (the fingerprint of scene.json,
///    of every file it names and of --max-iterations) is skipped.
///  * A body left "running" (killed) with the same inputs resumes from its
///    checkpoint.json.
///  * Otherwise (new inputs, a failed run, no checkpoint yet) the folder is emptied and
///    the body starts afresh.
///  * A failure (a mesh that cannot be read, joints outside the body, a layout that
///    cannot be placed, an optimization that fails) empties the folder but for
///    scene.json and writes the error into grade_body.json: nothing half-written.
/// A lock (DIR/bodies/NAME/.grade.lock, flock) keeps two invocations off one body.
#include <filesystem>
#include <string>

#include "tightfit/grade/bodies.hpp"
#include "tightfit/grade/scene.hpp"

namespace tightfit::app {

enum class BodyOutcome { kDone, kSkipped, kFailed };

/// Grades `body` with `design` in grading folder `dir` (already prepared and marked).
/// Returns the outcome; throws Interrupted after Ctrl-C / SIGTERM (the body stays
/// "running" and resumes next time) and InputError when the body's folder is locked by
/// another invocation or cannot be written.
BodyOutcome grade_body(const GradeDesign& design, const GradeBody& body,
                       const std::filesystem::path& dir, int max_iterations);

}  // namespace tightfit::app
