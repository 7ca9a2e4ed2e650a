#include "tightfit/common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <ext/stdio_filebuf.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ostream>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"

namespace tightfit {

namespace {

/// ": REASON" from errno after a failed operation (e.g. "No space left on device"), or
/// nothing when the system gave no reason.
std::string system_reason() {
  const int error = errno;
  return error != 0 ? std::string(": ") + std::strerror(error) : std::string();
}

/// fsync of a file or folder by path; false when it cannot be opened or synced.
bool sync_path(const std::filesystem::path& path, bool directory) {
  const int fd = ::open(path.c_str(),
                        (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

/// The process's umask, read without changing it (umask(2) would race with other threads).
mode_t process_umask() {
  static const mode_t mask = [] {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
      if (line.starts_with("Umask:"))
        return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
    return static_cast<mode_t>(022);
  }();
  return mask;
}

/// Opens a new file ".NAME.tightfit-XXXXXX" beside `path` with O_CREAT | O_EXCL (mkostemp);
/// returns its descriptor and stores its name in `tmp`.
int create_exclusive(const std::filesystem::path& path, std::filesystem::path& tmp) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  std::string name = (folder / ("." + path.filename().string() + ".tightfit-XXXXXX")).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  errno = 0;
  const int fd = ::mkostemp(buffer.data(), O_CLOEXEC);
  if (fd < 0) throw InputError(path.string(), "cannot open for writing" + system_reason());
  ::fchmod(fd, 0666 & ~process_umask());  // an ordinary new file's mode, not mkostemp's 0600
  tmp = std::filesystem::path(buffer.data());
  return fd;
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  std::filesystem::path tmp;
  ::close(create_exclusive(path, tmp));
  return tmp;
}

void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  // The data reaches the disk before the name does, and the rename before we return: a
  // crash or power loss leaves the old file or the new one, never a torn one.
  if (!sync_path(temporary, false)) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw InputError(path.string(), "cannot flush the finished file to disk");
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = system_reason();
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw InputError(path.string(), "cannot move the finished file into place" + reason);
  }
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  sync_path(folder, true);  // best effort: some file systems cannot sync a folder
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary) {
  std::filesystem::path tmp;
  const int fd = create_exclusive(path, tmp);
  try {
    {
      // The stream writes through the descriptor created above: the name is never reopened.
      __gnu_cxx::stdio_filebuf<char> buffer(
          fd, binary ? std::ios::out | std::ios::binary : std::ios::out);
      std::ostream out(&buffer);
      errno = 0;
      write(out);
      out.flush();
      if (!out) throw InputError(path.string(), "write failed" + system_reason());
    }  // closes fd
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
