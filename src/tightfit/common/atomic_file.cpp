#include "tightfit/common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"

namespace tightfit {

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  static std::atomic<int> counter{0};
  auto tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

namespace {

/// fsync of a file or folder by path; false when it cannot be opened or synced.
bool sync_path(const std::filesystem::path& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

/// ": REASON" from errno after a failed stream operation (e.g. "No space left on
/// device"), or nothing when the system gave no reason.
std::string system_reason() {
  const int error = errno;
  return error != 0 ? std::string(": ") + std::strerror(error) : std::string();
}

}  // namespace

void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  // The data reaches the disk before the name does, and the rename before we return: a
  // crash or power loss leaves the old file or the new one, never a torn one.
  if (!sync_path(temporary, false)) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw InputError(path.string(), "cannot flush the finished file to disk");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw InputError(path.string(), "cannot move the finished file into place");
  }
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  sync_path(folder, true);  // best effort: some file systems cannot sync a folder
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary) {
  const auto tmp = temporary_path_for(path);
  try {
    {
      errno = 0;
      std::ofstream out(tmp, binary ? std::ios::out | std::ios::binary : std::ios::out);
      if (!out) throw InputError(path.string(), "cannot open for writing" + system_reason());
      write(out);
      out.flush();
      if (!out) throw InputError(path.string(), "write failed" + system_reason());
    }
    commit_temporary(tmp, path);
  } catch (const NonFiniteOutput& e) {
    // A NaN or infinity about to be written: the file is not made (finite_output.hpp).
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw SolverError(path.string() + ": not written: " + e.what());
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace tightfit
