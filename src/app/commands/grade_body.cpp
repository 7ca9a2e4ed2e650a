#include "grade_body.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "optimize_run.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/interrupt.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/grade/status.hpp"
#include "tightfit/grade/summary.hpp"
#include "tightfit/scene/skeleton_fit.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLockFile = ".grade.lock";

/// An exclusive lock on a body's folder for the life of the object.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& folder) {
    const fs::path file = folder / kLockFile;
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError(folder.string(), "cannot create the lock file " + file.string());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw InputError(folder.string(),
                       "another tightfit grade is working on this body (its lock " + file.string() +
                           " is held)");
    }
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

/// Removes everything in `folder` but the lock and the names in `keep`.
void empty_folder(const fs::path& folder, const std::vector<std::string>& keep) {
  std::vector<fs::path> doomed;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (name == kLockFile || std::find(keep.begin(), keep.end(), name) != keep.end()) continue;
    doomed.push_back(e.path());
  }
  for (const fs::path& p : doomed) fs::remove_all(p);
}

/// Checks what the optimization would only find out late or not at all: the meshes can
/// be read, and the joints lie inside the body they were placed on.
void check_body(const GradeBody& body) {
  const TriMesh mesh = read_tri_mesh(body.mesh);
  const TriMesh rig = body.rig_mesh == body.mesh ? mesh : read_tri_mesh(body.rig_mesh);
  check_joints_inside(rig, read_skeleton(body.joints), body.joints, body.rig_mesh);
}

}  // namespace

BodyOutcome grade_body(const GradeDesign& design, const GradeBody& body, const fs::path& dir,
                       int max_iterations) {
  const auto t_start = SteadyClock::now();
  const fs::path folder = grade_body_folder(dir, body.name);
  std::error_code ec;
  // Never empty a folder of the user's (DIR given with --force may hold one).
  if (fs::exists(folder, ec) && !is_tightfit_folder(folder))
    throw InputError(folder.string(),
                     "is not empty and was not written by tightfit grade: "
                     "refusing to grade body " +
                         body.name + " into it");
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder.string(), "cannot create the body's folder: " + ec.message());
  const FolderLock lock(folder);

  const nlohmann::json scene = grade_body_scene(design, body, folder);
  const std::string fingerprint =
      grade_fingerprint(scene, folder, "max_iterations=" + std::to_string(max_iterations));
  const fs::path status_file = folder / kGradeBodyFile;
  const std::optional<GradeBodyStatus> before = read_grade_body_status(status_file);
  const bool same_inputs = before && before->fingerprint == fingerprint;
  if (same_inputs && before->status == "done") {
    std::printf("tightfit grade: body %s is graded already (%s): skipped\n", body.name.c_str(),
                folder.c_str());
    return BodyOutcome::kSkipped;
  }
  const bool resume = same_inputs && before->status == "running" &&
                      fs::is_regular_file(folder / "checkpoint.json", ec);
  if (!resume) empty_folder(folder, {});
  const fs::path scene_file = folder / "scene.json";
  write_text_atomically(scene_file, scene.dump(2) + "\n");
  mark_output_folder(folder, "grade");
  write_grade_body_status(status_file, {body.name, "running", fingerprint, "", 0.0});
  std::printf("tightfit grade: body %s%s\n", body.name.c_str(),
              resume ? " (resuming from its checkpoint)" : "");
  std::fflush(stdout);

  try {
    check_body(body);
    run_optimize({scene_file.string(), folder.string(), resume ? folder.string() : "",
                  max_iterations, false, ""});
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    empty_folder(folder, {"scene.json", kOutputMarker});
    write_grade_body_status(status_file,
                            {body.name, "failed", fingerprint, e.what(), seconds_since(t_start)});
    std::printf("tightfit grade: body %s FAILED: %s\n", body.name.c_str(), e.what());
    std::fflush(stdout);
    return BodyOutcome::kFailed;
  }
  write_grade_body_status(status_file,
                          {body.name, "done", fingerprint, "", seconds_since(t_start)});
  std::printf("tightfit grade: body %s done in %.1f s (%s)\n", body.name.c_str(),
              seconds_since(t_start), folder.c_str());
  std::fflush(stdout);
  return BodyOutcome::kDone;
}

}  // namespace tightfit::app
