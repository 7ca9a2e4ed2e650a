#pragma once
/// The low-level pieces of common/output_directory.hpp: private staging folders beside an
/// output folder, recorded as tightfit's own by a manifest inside them and locked while
/// their run lives; advisory folder locks; cloning a folder's entries with hard links.
#include <sys/types.h>

#include <filesystem>
#include <string>

namespace tightfit {

/// A staging folder ".NAME.tightfit-XXXXXX" made with mkdtemp beside `target` (NAME its
/// file name), locked (flock) and holding the manifest "tightfit-staging" (this process's
/// id and `target`'s absolute path).
struct StagingFolder {
  std::filesystem::path path;
  int fd = -1;  ///< open, locked
};

/// Makes the staging folder of `target` (absolute, symbolic links resolved) in folder
/// `in` (its parent folder, or `target` itself where the parent cannot take it). Throws
/// InputError naming `target` when `in` does not allow it.
StagingFolder make_staging_folder(const std::filesystem::path& target,
                                  const std::filesystem::path& in);

/// Removes the staging folders of `target` in `in` that killed runs left: only folders
/// named like tightfit's, owned by this user, holding a manifest for `target` and not
/// locked by a living process. Returns how many it removed.
int remove_abandoned_staging(const std::filesystem::path& target, const std::filesystem::path& in);

/// The id of a living process whose staging folder in `in` names `target`, or -1.
long staging_owner(const std::filesystem::path& target, const std::filesystem::path& in);

/// flock(fd, LOCK_EX | LOCK_NB): false when another open file description holds it.
bool try_lock(int fd);

/// Opens the folder `path` (following a link the user gave) for locking; -1 when it fails.
int open_folder(const std::filesystem::path& path);

/// Recreates the entry `name` of folder `from` in folder `to`: a hard link for a file
/// (a copy where linking is refused), the same link for a symbolic link, a folder of
/// clones for a folder. False for an entry it cannot recreate (a device, a FIFO, a
/// socket, a folder on another file system, a failed copy); what it made then stays for
/// the caller to remove.
bool clone_entry(int from, int to, const std::string& name);

/// Whether `a` and `b` lie on the same file system (stat, following links).
bool same_device(const std::filesystem::path& a, const std::filesystem::path& b);

/// Whether `a` and `b` name the same file or folder (stat, following links).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace tightfit
