#include "tightfit/common/output_directory.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/staging_folder.hpp"

namespace tightfit {
namespace fs = std::filesystem;

namespace {

/// Whether `file` is a JSON object whose "format" names a tightfit document.
bool has_tightfit_format(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec) || fs::file_size(file, ec) > (std::uintmax_t{1} << 30))
    return false;
  nlohmann::json j;
  try {
    j = read_json_file(file.string());
  } catch (const InputError&) {
    return false;
  }
  return j.is_object() && j.contains("format") && j["format"].is_string() &&
         j["format"].get<std::string>().starts_with("tightfit-");
}

std::string marker_text(const std::string& command) {
  return "This folder was written by `tightfit " + command +
         "`. tightfit replaces its own files here and deletes nothing else.\n";
}

/// The test hook of the commit: TIGHTFIT_TEST_KILL_COMMIT_AT=K sends this process SIGKILL
/// just before the K-th change (0-based) a commit makes to the file system, so that a
/// test can look at the folder a kill at that moment leaves. `step` counts the changes.
void commit_step(long& step) {
  const char* value = std::getenv("TIGHTFIT_TEST_KILL_COMMIT_AT");
  if (value != nullptr && std::strtol(value, nullptr, 10) == step) ::raise(SIGKILL);
  ++step;
}

/// The absolute path of `target` with symbolic links resolved ("dir/." is dir).
fs::path resolve(const fs::path& target) {
  std::error_code ec;
  fs::path real = fs::weakly_canonical(fs::absolute(target), ec);
  if (ec) real = fs::absolute(target).lexically_normal();
  if (real.filename().empty()) real = real.parent_path();
  return real;
}

/// The folder is locked by another run (`held`), or appeared while this run was going.
[[noreturn]] void throw_busy(const fs::path& target, const fs::path& real, bool held) {
  // A run stages beside its folder, or inside it where the parent cannot take it.
  if (!held)
    throw InputError(target.string(),
                     "was created by another tightfit run while this one was going: results "
                     "not written (run again, or choose another output folder)");
  long pid = staging_owner(real, real.parent_path());
  if (pid <= 0) pid = staging_owner(real, real);
  throw InputError(target.string(),
                   "is in use by another tightfit run (" +
                       (pid > 0 ? "process " + std::to_string(pid) : std::string("a process")) +
                       " holds its lock): wait for it to finish or choose another output folder");
}

}  // namespace

bool is_tightfit_folder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  if (fs::is_empty(folder, ec) && !ec) return true;
  if (fs::is_regular_file(fs::symlink_status(folder / kOutputMarker, ec))) return true;
  for (const char* name : {"state.json", "checkpoint.json"})
    if (has_tightfit_format(folder / name)) return true;
  return false;
}

bool prepare_output_folder(const fs::path& target, bool force) {
  if (target.empty()) throw InputError("--out", "no output folder given");
  std::error_code ec;
  if (fs::exists(target, ec)) {
    if (!fs::is_directory(target, ec))
      throw InputError(target.string(), "is a file, not a folder: choose another output folder");
    if (!force && !is_tightfit_folder(target))
      throw InputError(target.string(),
                       "is not empty and was not written by tightfit: refusing to write into it "
                       "(choose another output folder, or pass --force: tightfit then writes only "
                       "its own files there and deletes nothing)");
    return false;
  }
  fs::create_directories(target, ec);
  if (ec) throw InputError(target.string(), "cannot create the output folder: " + ec.message());
  return true;
}

void mark_output_folder(const fs::path& folder, const std::string& command) {
  write_text_atomically(folder / kOutputMarker, marker_text(command));
}

OutputDirectory::OutputDirectory(fs::path target, bool force, std::string command)
    : target_(std::move(target)), command_(std::move(command)) {
  if (target_.empty()) throw InputError("--out", "no output folder given");
  real_ = resolve(target_);
  std::error_code ec;
  if (fs::exists(real_, ec)) {
    prepare_output_folder(real_, force);  // the rule; creates nothing here
    target_fd_ = open_folder(real_);
    if (target_fd_ < 0)
      throw InputError(target_.string(), std::string("cannot open: ") + std::strerror(errno));
    if (!try_lock(target_fd_)) {
      ::close(target_fd_);
      throw_busy(target_, real_, true);
    }
  } else {
    fs::create_directories(real_.parent_path(), ec);
    if (ec) throw InputError(target_.string(), "cannot create the output folder: " + ec.message());
  }
  remove_abandoned_staging(real_, real_.parent_path());
  if (target_fd_ >= 0) remove_abandoned_staging(real_, real_);
  try {
    StagingFolder folder;
    try {
      if (target_fd_ >= 0 && !same_device(real_, real_.parent_path()))
        throw InputError(target_.string(), "a mount point");  // stage inside it (below)
      folder = make_staging_folder(real_, real_.parent_path());
    } catch (const InputError&) {
      if (target_fd_ < 0) throw;
      folder = make_staging_folder(real_, real_);  // moves one by one at commit
      staged_inside_ = true;
    }
    private_ = folder.path;
    private_fd_ = folder.fd;
    staging_ = private_ / "out";
    fs::create_directory(staging_);
  } catch (...) {
    if (target_fd_ >= 0) ::close(target_fd_);
    if (private_fd_ >= 0) ::close(private_fd_);
    if (!private_.empty()) fs::remove_all(private_, ec);
    throw;
  }
}

OutputDirectory::~OutputDirectory() {
  std::error_code ec;
  if (!committed_ && created_target_ && !keep_published_ && target_fd_ >= 0) {
    published_.insert(kOutputMarker);
    for (const std::string& name : published_) ::unlinkat(target_fd_, name.c_str(), 0);
    ::rmdir(real_.c_str());  // only when nothing else arrived there
  }
  fs::remove_all(private_, ec);
  if (private_fd_ >= 0) ::close(private_fd_);
  if (target_fd_ >= 0) ::close(target_fd_);
}

void OutputDirectory::create_target_with(const std::string& name,
                                         const std::function<void(const fs::path&)>& write) {
  const fs::path fresh = private_ / "new";
  fs::create_directory(fresh);
  write_text_atomically(fresh / kOutputMarker, marker_text(command_));
  write(fresh / name);
  const int fd = open_folder(fresh);
  if (fd < 0 || !try_lock(fd) ||
      ::renameat2(AT_FDCWD, fresh.c_str(), AT_FDCWD, real_.c_str(), RENAME_NOREPLACE) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    if (error == EEXIST) throw_busy(target_, real_, false);
    throw InputError(target_.string(),
                     std::string("cannot create the output folder: ") + std::strerror(error));
  }
  target_fd_ = fd;  // locked before its name appeared
  created_target_ = true;
}

void OutputDirectory::publish(const std::string& name,
                              const std::function<void(const fs::path&)>& write) {
  if (target_fd_ < 0) {
    create_target_with(name, write);
  } else {
    const fs::path scratch = private_ / "publish";
    fs::create_directories(scratch);
    if (!published_.contains(kOutputMarker) && !created_target_) {
      write_text_atomically(scratch / kOutputMarker, marker_text(command_));
      if (::renameat(AT_FDCWD, (scratch / kOutputMarker).c_str(), target_fd_, kOutputMarker) != 0)
        throw InputError((real_ / kOutputMarker).string(), std::strerror(errno));
      published_.insert(kOutputMarker);
    }
    write(scratch / name);
    if (::renameat(AT_FDCWD, (scratch / name).c_str(), target_fd_, name.c_str()) != 0)
      throw InputError((target_ / name).string(),
                       std::string("cannot move the file into place: ") + std::strerror(errno));
  }
  published_.insert(name);
}

std::vector<std::string> OutputDirectory::commit() {
  std::set<std::string> staged;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(staging_))
    staged.insert(e.path().filename().string());
  std::vector<std::string> moved(staged.begin(), staged.end());
  mark_output_folder(staging_, command_);
  staged.insert(kOutputMarker);
  if (target_fd_ < 0) {
    // A new folder: it appears complete, or not at all.
    commit_step(steps_);
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, real_.c_str(), RENAME_NOREPLACE) != 0) {
      if (errno == EEXIST) throw_busy(target_, real_, false);
      throw InputError(target_.string(),
                       std::string("cannot create the output folder: ") + std::strerror(errno));
    }
  } else {
    // Every obstacle is found before anything changes.
    for (const std::string& name : staged) {
      const auto into = fs::symlink_status(real_ / name, ec);
      const bool folder = fs::is_directory(fs::symlink_status(staging_ / name, ec));
      if (fs::exists(into) && fs::is_directory(into) != folder)
        throw InputError((target_ / name).string(),
                         "exists and is not a " + std::string(folder ? "folder" : "file") +
                             ": cannot put the result there (nothing was changed)");
    }
    if (!swap_into_target(staged)) move_into_target(staged);
  }
  committed_ = true;
  fs::remove_all(private_, ec);
  return moved;
}

bool OutputDirectory::swap_into_target(const std::set<std::string>& staged) {
  struct stat target_stat {};
  std::error_code ec;
  if (staged_inside_ || in_place_ || same_file(real_, fs::current_path(ec)) ||
      ::fstat(target_fd_, &target_stat) != 0 || target_stat.st_uid != ::geteuid())
    return false;  // a shell in the folder would be left in the old one; not ours to replace
  const int staging_fd = open_folder(staging_);
  std::vector<std::string> cloned;
  bool ok = staging_fd >= 0 && ::fchmod(staging_fd, target_stat.st_mode & 07777) == 0;
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(real_, ec))
    names.push_back(e.path().filename().string());
  for (const std::string& name : names) {
    if (!ok || staged.contains(name)) continue;
    commit_step(steps_);
    ok = clone_entry(target_fd_, staging_fd, name);
    cloned.push_back(name);
  }
  if (ok) {
    commit_step(steps_);
    ok = ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, real_.c_str(), RENAME_EXCHANGE) == 0;
  }
  if (!ok)  // undo the clones; the moves one by one follow
    for (const std::string& name : cloned) fs::remove_all(staging_ / name, ec);
  if (staging_fd >= 0) ::close(staging_fd);
  return ok;
}

void OutputDirectory::move_into_target(const std::set<std::string>& staged) {
  std::error_code ec;
  for (const std::string& name : staged) {
    const fs::path from = staging_ / name;
    if (fs::is_directory(fs::symlink_status(real_ / name, ec))) {
      commit_step(steps_);
      fs::remove_all(real_ / name, ec);
    }
    commit_step(steps_);
    if (::renameat(AT_FDCWD, from.c_str(), target_fd_, name.c_str()) != 0)
      throw InputError((target_ / name).string(),
                       std::string("cannot move the result into place: ") + std::strerror(errno));
  }
}

}  // namespace tightfit
