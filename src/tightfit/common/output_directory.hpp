#pragma once
/// Output folders that never lose a user's files — one rule for every command:
///
///  * The folder may be missing (it is created), empty, or a tightfit folder: one that
///    holds tightfit's marker file `.tightfit` (written with every run's outputs) or a
///    `state.json` / `checkpoint.json` of a tightfit run. Any other non-empty folder is
///    refused (InputError) unless `force`; a path that is a file, or a folder that cannot
///    be created, is an InputError naming it.
///  * A command writes into a staging folder INSIDE the target (so `--out .` works and
///    every move is a rename on one file system) and `commit()` moves each of its files
///    into the target, replacing only files of the same name. Nothing else in the folder
///    is touched or deleted, with or without `force` (files an earlier run wrote that
///    this run does not make stay as they are).
///  * A command that fails before commit() leaves the target as it was: the staging
///    folder is removed, and the target too when this object created it.
#include <filesystem>
#include <string>
#include <vector>

namespace tightfit {

/// Name of the marker file that makes a folder a tightfit folder.
inline constexpr const char* kOutputMarker = ".tightfit";

/// Whether `folder` is empty or a tightfit folder (rule above). False for a missing path.
bool is_tightfit_folder(const std::filesystem::path& folder);

/// Checks `target` against the rule and creates it when missing. Returns true when it
/// created the folder. Throws InputError naming `target`.
bool prepare_output_folder(const std::filesystem::path& target, bool force);

/// Removes what killed tightfit runs left unfinished in `folder`: files "NAME.tmp.PID.N"
/// (atomic_file.hpp) and staging folders ".tightfit-staging.PID.N" whose process PID is
/// no longer running. Nothing else is touched. Returns how many it removed.
int remove_stale_temporaries(const std::filesystem::path& folder);

/// Writes the marker file into `folder` (atomically; a text naming `command`), after
/// remove_stale_temporaries(folder).
void mark_output_folder(const std::filesystem::path& folder, const std::string& command);

class OutputDirectory {
 public:
  /// `target`: the folder the results go to (prepare_output_folder's rule); `command`
  /// names the marker's writer.
  explicit OutputDirectory(std::filesystem::path target, bool force = false,
                           std::string command = "tightfit");
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// The folder to write into until commit().
  const std::filesystem::path& staging() const { return staging_; }
  /// staging() / name.
  std::filesystem::path file(const std::string& name) const { return staging_ / name; }
  /// Moves every staged file into the target (replacing files of the same name only),
  /// writes the marker and removes the staging folder. Returns the names moved, sorted.
  std::vector<std::string> commit();
  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::string command_;
  bool created_target_ = false;
  bool committed_ = false;
};

}  // namespace tightfit
