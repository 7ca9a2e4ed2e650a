#pragma once
/// Output folders that never lose a user's files and never hold a mix of two runs — one
/// rule for every command:
///
///  * The folder may be missing (it is created), empty, or a tightfit folder: one that
///    holds tightfit's marker file `.tightfit` (written with every run's outputs) or a
///    `state.json` / `checkpoint.json` of a tightfit run. Any other non-empty folder is
///    refused (InputError) unless `force`; a path that is a file is an InputError naming it.
///  * One writer per folder: a run holds an advisory lock (flock) on an existing output
///    folder from the start to the end; a second run into it is refused (InputError, exit
///    2) naming the process that holds it.
///  * A command writes into a private staging folder created with mkdtemp BESIDE the
///    target (".NAME.tightfit-XXXXXX" in the target's parent folder, so every move is a
///    rename on one file system). commit() publishes all of it at once: a missing target
///    appears complete with one rename (RENAME_NOREPLACE); an existing one is swapped
///    with one rename (RENAME_EXCHANGE) for a copy of itself (hard links) holding the new
///    files. At every moment, also under SIGKILL, the folder is as it was or complete.
///    Files of the same name are replaced; nothing else in the folder is touched or
///    deleted (files an earlier run wrote that this run does not make stay as they are).
///    Where the swap is impossible (the folder is the current directory, another user's,
///    a mount point or in a parent folder that cannot take the staging folder — which is
///    then made inside it —, the file system has no RENAME_EXCHANGE, an entry cannot be
///    linked or copied) the files are moved one by one after every obstacle has been
///    checked.
///  * A command that fails before commit() leaves the target as it was; a target it
///    created is removed. A killed run leaves at most its staging folder, which holds a
///    manifest naming its target: the next run into the same target removes it once no
///    process holds its lock. No other entry is ever removed.
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace tightfit {

/// Name of the marker file that makes a folder a tightfit folder.
inline constexpr const char* kOutputMarker = ".tightfit";

/// Whether `folder` is empty or a tightfit folder (rule above). False for a missing path.
bool is_tightfit_folder(const std::filesystem::path& folder);

/// Checks `target` against the rule and creates it when missing (for commands that
/// manage a folder of folders, such as grade). Returns true when it created the folder.
/// Throws InputError naming `target`.
bool prepare_output_folder(const std::filesystem::path& target, bool force);

/// Writes the marker file into `folder` (atomically; a text naming `command`).
void mark_output_folder(const std::filesystem::path& folder, const std::string& command);

class OutputDirectory {
 public:
  /// `target`: the folder the results go to (the rule above); `command` names the
  /// marker's writer. Throws InputError when the rule refuses the folder, another run
  /// holds it, or no staging folder can be made beside it.
  explicit OutputDirectory(std::filesystem::path target, bool force = false,
                           std::string command = "tightfit");
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// The folder to write into until commit().
  const std::filesystem::path& staging() const { return staging_; }
  /// staging() / name.
  std::filesystem::path file(const std::string& name) const { return staging_ / name; }
  /// Publishes the outputs (rule above) with the marker and removes the staging folder.
  /// Returns the names published, sorted. Throws InputError naming an obstacle (a folder
  /// where a file goes, or the reverse) before anything changed.
  std::vector<std::string> commit();
  /// Puts a file into target() at once, for files a long run keeps up to date while it
  /// goes on (a checkpoint): `write(path)` writes it at a private path, which is then
  /// renamed to target()/name. A missing target is created holding the marker and this
  /// file (atomically). Such files are removed, with a target this object created, when
  /// the run fails, unless keep_published() was called.
  void publish(const std::string& name,
               const std::function<void(const std::filesystem::path&)>& write);
  /// Makes commit() move the files in one by one (after checking every obstacle) instead of
  /// swapping the folder: for a folder whose subfolders other processes may be writing
  /// into at the same time (the grading folder, whose body folders are graded apart).
  void commit_in_place() { in_place_ = true; }
  /// Keeps the published files (and the target) of a run that fails: its checkpoint.
  void keep_published() { keep_published_ = true; }
  const std::filesystem::path& target() const { return target_; }

 private:
  void create_target_with(const std::string& name,
                          const std::function<void(const std::filesystem::path&)>& write);
  bool swap_into_target(const std::set<std::string>& staged);
  void move_into_target(const std::set<std::string>& staged);

  std::filesystem::path target_;   ///< as given
  std::filesystem::path real_;     ///< absolute, symbolic links resolved
  std::filesystem::path private_;  ///< the mkdtemp folder beside real_ (manifest, staging)
  std::filesystem::path staging_;  ///< private_ / "out"
  std::string command_;
  int target_fd_ = -1;   ///< the locked target (-1 while it does not exist)
  int private_fd_ = -1;  ///< the locked private folder
  bool created_target_ = false;
  bool committed_ = false;
  bool keep_published_ = false;
  bool staged_inside_ = false;  ///< the staging folder is inside the target (no swap)
  bool in_place_ = false;       ///< commit_in_place()
  long steps_ = 0;              ///< changes made by commit() so far (its test hook counts them)
  std::set<std::string> published_;
};

}  // namespace tightfit
