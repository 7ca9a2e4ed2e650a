#include "tightfit/common/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "tightfit/common/error.hpp"

namespace tightfit {

namespace {

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

struct Read {
  std::string hash;
  std::uint64_t sequence = 0;  ///< 1 for the first read of the process
};

std::map<std::string, Read>& registry() {
  static std::map<std::string, Read> files;
  return files;
}

std::uint64_t& read_count() {
  static std::uint64_t count = 0;
  return count;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

std::string megabytes(std::uintmax_t bytes) {
  char text[64];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

}  // namespace

std::string content_hash(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) throw InputError(path.string(), "file does not exist");
    throw InputError(path.string(),
                     std::string("cannot open for reading: ") + std::strerror(error));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const mode_t mode = st.st_mode;
    ::close(fd);
    throw InputError(path.string(), std::string("is ") + kind_of(mode) +
                                        ", not a regular file: only regular files are read");
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) {
    ::close(fd);
    throw InputError(path.string(), "is " + megabytes(size) + ", more than the " +
                                        megabytes(max_bytes) + " an input file may have");
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  const int error = errno;
  ::close(fd);
  if (done != bytes.size())
    throw InputError(path.string(), std::string("read error: ") +
                                        (error != 0 ? std::strerror(error) : "the file shrank"));
  std::error_code ec;
  std::filesystem::path key =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  if (ec) key = std::filesystem::absolute(path);
  const std::lock_guard lock(registry_mutex());
  registry()[key.string()] = {content_hash(bytes), ++read_count()};
  return bytes;
}

std::uint64_t input_reads() {
  const std::lock_guard lock(registry_mutex());
  return read_count();
}

std::map<std::string, std::string> input_files_read(std::uint64_t since) {
  const std::lock_guard lock(registry_mutex());
  std::map<std::string, std::string> files;
  for (const auto& [path, read] : registry())
    if (read.sequence > since) files[path] = read.hash;
  return files;
}

}  // namespace tightfit
