#pragma once
/// Atomic output: results are written to a temporary file beside the target and renamed
/// into place only when complete, so a failed run leaves no partial file.
///
/// The temporary file is created exclusively (O_CREAT | O_EXCL: never an existing file,
/// never through a symbolic link) under an unpredictable name ".NAME.tightfit-XXXXXX", so a
/// link planted in a shared folder cannot redirect a write. The rename replaces the entry
/// `path` itself: a symbolic link at `path` is replaced, not followed.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>

namespace tightfit {

/// Calls `write(stream)` on a temporary file next to `path`, then renames it to
/// `path`. On any exception the temporary file is removed and the exception rethrown;
/// a NonFiniteOutput (finite_output.hpp: `write` found a NaN or infinity in what it was
/// about to write) becomes a SolverError "PATH: not written: WHERE". `binary` opens the
/// stream in binary mode.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary = false);

/// Writes `text` to `path` atomically.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

/// Creates a new, empty file beside `path` exclusively under an unpredictable name (see
/// above) and returns its name, for writers such as cairo that need a file name; rename it
/// with `commit_temporary` (or remove it). Throws InputError naming `path` when the folder
/// does not allow it.
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

/// Flushes `temporary` to disk and renames it to `path` (atomic on one file system).
void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path);

}  // namespace tightfit
