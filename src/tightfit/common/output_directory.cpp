#include "tightfit/common/output_directory.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <fstream>
#include <regex>
#include <utility>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"

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

/// The process id in a name tightfit gives its unfinished files, or -1: "FILE.tmp.PID.N"
/// (atomic_file.hpp) or ".tightfit-staging.PID.N".
long writer_pid(const std::string& name) {
  static const std::regex pattern(R"((?:^\.tightfit-staging|\.tmp)\.([0-9]{1,9})\.[0-9]+$)");
  std::smatch m;
  if (!std::regex_search(name, m, pattern)) return -1;
  return std::stol(m[1].str());
}

bool process_alive(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

}  // namespace

int remove_stale_temporaries(const fs::path& folder) {
  int removed = 0;
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const long pid = writer_pid(e.path().filename().string());
    if (pid > 0 && pid != ::getpid() && !process_alive(pid)) stale.push_back(e.path());
  }
  for (const fs::path& p : stale) {
    std::error_code rm;
    if (fs::remove_all(p, rm) > 0 && !rm) ++removed;
  }
  return removed;
}

bool is_tightfit_folder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  if (fs::is_empty(folder, ec) && !ec) return true;
  if (fs::exists(folder / kOutputMarker, ec)) return true;
  bool only_staging = true;  // leftovers of a killed run are tightfit's too
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    only_staging &= e.path().filename().string().starts_with(".tightfit-staging.");
  if (only_staging && !ec) return true;
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
  remove_stale_temporaries(folder);
  write_text_atomically(folder / kOutputMarker,
                        "This folder was written by `tightfit " + command +
                            "`. tightfit replaces its own files here and deletes nothing else.\n");
}

OutputDirectory::OutputDirectory(fs::path target, bool force, std::string command)
    : target_(std::move(target)), command_(std::move(command)) {
  created_target_ = prepare_output_folder(target_, force);
  static std::atomic<int> counter{0};
  staging_ = target_ /
             (".tightfit-staging." + std::to_string(::getpid()) + "." + std::to_string(counter++));
  std::error_code ec;
  fs::create_directory(staging_, ec);
  if (ec) {
    if (created_target_) fs::remove(target_, ec);
    throw InputError(target_.string(), "cannot create a staging folder in it: " + ec.message());
  }
}

OutputDirectory::~OutputDirectory() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (created_target_ && fs::is_empty(target_, ec)) fs::remove(target_, ec);
}

std::vector<std::string> OutputDirectory::commit() {
  std::vector<std::string> moved;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(staging_)) {
    const fs::path to = target_ / e.path().filename();
    if (fs::exists(to, ec) && fs::is_directory(to, ec) != e.is_directory())
      throw InputError(to.string(), "exists and is not a " +
                                        std::string(e.is_directory() ? "folder" : "file") +
                                        ": cannot put the result there");
    if (e.is_directory()) fs::remove_all(to, ec);
    fs::rename(e.path(), to, ec);
    if (ec) throw InputError(to.string(), "cannot move the result into place: " + ec.message());
    moved.push_back(e.path().filename().string());
  }
  mark_output_folder(target_, command_);
  committed_ = true;
  fs::remove_all(staging_, ec);
  std::sort(moved.begin(), moved.end());
  return moved;
}

}  // namespace tightfit
