#include "tightfit/common/staging_folder.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace fs = std::filesystem;

namespace {

constexpr const char* kManifest = "tightfit-staging";
constexpr const char* kManifestTitle = "tightfit staging folder";
constexpr off_t kMaxManifestBytes = 1 << 16;

std::string prefix_of(const fs::path& target) {
  return "." + target.filename().string() + ".tightfit-";
}

std::string manifest_text(const fs::path& target) {
  return std::string(kManifestTitle) + "\npid: " + std::to_string(::getpid()) +
         "\ntarget: " + target.string() + "\n";
}

/// The manifest of the staging folder open at `fd` when it names `target`: its process
/// id (> 0), or -1 when the folder holds no such manifest (it is then not tightfit's).
long manifest_pid(int fd, const fs::path& target) {
  const int file = ::openat(fd, kManifest, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (file < 0) return -1;
  struct stat st {};
  std::string text;
  if (::fstat(file, &st) == 0 && S_ISREG(st.st_mode) && st.st_size < kMaxManifestBytes) {
    text.resize(static_cast<size_t>(st.st_size));
    if (::read(file, text.data(), text.size()) != static_cast<ssize_t>(text.size())) text.clear();
  }
  ::close(file);
  std::istringstream in(text);
  std::string title, pid_line, target_line;
  std::getline(in, title);
  std::getline(in, pid_line);
  std::getline(in, target_line);
  if (title != kManifestTitle || !pid_line.starts_with("pid: ") ||
      target_line != "target: " + target.string())
    return -1;
  char* end = nullptr;
  const long pid = std::strtol(pid_line.c_str() + 5, &end, 10);
  return pid > 0 && end && *end == '\0' ? pid : -1;
}

/// Calls `visit(path, fd, pid)` for each staging folder of `target` that is tightfit's: named
/// like one, a real folder (not a link) owned by this user, holding a manifest for
/// `target`. `fd` is open for the call only.
template <typename Visit>
void for_each_staging(const fs::path& target, const fs::path& parent, Visit visit) {
  const std::string prefix = prefix_of(target);
  std::error_code ec;
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with(prefix) && name.size() == prefix.size() + 6) names.push_back(name);
  }
  for (const std::string& name : names) {
    const fs::path path = parent / name;
    const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_uid == ::geteuid()) {
      const long pid = manifest_pid(fd, target);
      if (pid > 0) visit(path, fd, pid);
    }
    ::close(fd);
  }
}

}  // namespace

bool try_lock(int fd) { return ::flock(fd, LOCK_EX | LOCK_NB) == 0; }

int open_folder(const fs::path& path) {
  return ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
}

StagingFolder make_staging_folder(const fs::path& target, const fs::path& in) {
  std::string name = (in / (prefix_of(target) + "XXXXXX")).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  if (::mkdtemp(buffer.data()) == nullptr)
    throw InputError(target.string(), std::string("cannot create a staging folder in ") +
                                          in.string() + ": " + std::strerror(errno));
  StagingFolder folder{fs::path(buffer.data()), -1};
  folder.fd = ::open(buffer.data(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  // Locked before the manifest exists: no other run ever takes a living folder for dead.
  const int file = folder.fd < 0 || !try_lock(folder.fd)
                       ? -1
                       : ::openat(folder.fd, kManifest,
                                  O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  const std::string text = manifest_text(target);
  const bool ok =
      file >= 0 && ::write(file, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  if (file >= 0) ::close(file);
  if (!ok) {
    if (folder.fd >= 0) ::close(folder.fd);
    std::error_code ec;
    fs::remove_all(folder.path, ec);
    throw InputError(target.string(),
                     "cannot write the manifest of its staging folder " + folder.path.string());
  }
  return folder;
}

int remove_abandoned_staging(const fs::path& target, const fs::path& in) {
  std::vector<fs::path> abandoned;
  for_each_staging(target, in, [&](const fs::path& path, int fd, long pid) {
    // Its lock is free: the run that made it is gone (a lock dies with its process).
    if (pid != ::getpid() && try_lock(fd)) abandoned.push_back(path);
  });
  int removed = 0;
  for (const fs::path& path : abandoned) {
    std::error_code ec;
    fs::remove_all(path, ec);
    removed += ec ? 0 : 1;
  }
  return removed;
}

long staging_owner(const fs::path& target, const fs::path& in) {
  long owner = -1;
  for_each_staging(target, in, [&](const fs::path&, int fd, long pid) {
    if (!try_lock(fd) && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM)) owner = pid;
  });
  return owner;
}

bool same_device(const fs::path& a, const fs::path& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev;
}

bool same_file(const fs::path& a, const fs::path& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

namespace {

bool copy_file_at(int from, int to, const std::string& name, mode_t mode) {
  const int in = ::openat(from, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (in < 0) return false;
  const int out =
      ::openat(to, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  bool ok = out >= 0;
  std::vector<char> buffer(1 << 16);
  while (ok) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n <= 0) {
      ok = n == 0;
      break;
    }
    ok = ::write(out, buffer.data(), static_cast<size_t>(n)) == n;
  }
  ::close(in);
  if (out >= 0) ::close(out);
  return ok;
}

bool clone_folder(int from, int to, const std::string& name, mode_t mode) {
  if (::mkdirat(to, name.c_str(), mode & 07777) != 0) return false;
  const int src = ::openat(from, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  const int dst = ::openat(to, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  bool ok = src >= 0 && dst >= 0;
  DIR* dir = ok ? ::fdopendir(::dup(src)) : nullptr;
  ok = ok && dir != nullptr;
  std::vector<std::string> names;
  while (ok) {
    const dirent* e = ::readdir(dir);
    if (e == nullptr) break;
    const std::string n = e->d_name;
    if (n != "." && n != "..") names.push_back(n);
  }
  if (dir) ::closedir(dir);
  for (const std::string& n : names) ok = ok && clone_entry(src, dst, n);
  if (src >= 0) ::close(src);
  if (dst >= 0) ::close(dst);
  return ok;
}

}  // namespace

bool clone_entry(int from, int to, const std::string& name) {
  struct stat st {};
  if (::fstatat(from, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return false;
  if (S_ISREG(st.st_mode))
    return ::linkat(from, name.c_str(), to, name.c_str(), 0) == 0 ||
           copy_file_at(from, to, name, st.st_mode & 07777);
  if (S_ISLNK(st.st_mode)) {
    std::string link(4096, '\0');  // PATH_MAX: a longer target is not cloned
    const ssize_t n = ::readlinkat(from, name.c_str(), link.data(), link.size());
    if (n < 0 || static_cast<std::size_t>(n) >= link.size()) return false;
    link.resize(static_cast<std::size_t>(n));
    return ::symlinkat(link.data(), to, name.c_str()) == 0;
  }
  struct stat folder {};
  // A folder on another file system (a mount point) is not cloned: removing the old copy
  // afterwards would delete what is mounted there.
  if (S_ISDIR(st.st_mode))
    return ::fstat(from, &folder) == 0 && folder.st_dev == st.st_dev &&
           clone_folder(from, to, name, st.st_mode);
  return false;
}

}  // namespace tightfit
