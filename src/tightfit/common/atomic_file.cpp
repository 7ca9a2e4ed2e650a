#include "tightfit/common/atomic_file.hpp"

#include <atomic>
#include <fstream>
#include <unistd.h>

#include "tightfit/common/error.hpp"

namespace tightfit {

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  static std::atomic<int> counter{0};
  auto tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw InputError(path.string(), "cannot move the finished file into place");
  }
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary) {
  const auto tmp = temporary_path_for(path);
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::out | std::ios::binary : std::ios::out);
      if (!out) throw InputError(path.string(), "cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw InputError(path.string(), "write failed");
    }
    commit_temporary(tmp, path);
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
