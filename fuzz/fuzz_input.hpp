#pragma once
/// Shared harness of the libFuzzer targets (fuzz/*_fuzz.cpp, `make fuzz`).
///
/// tightfit's readers take file paths, so each input is written to a scratch file with
/// the reader's extension (in TMPDIR, one per process) and read back. The contract
/// under test: a reader either succeeds or throws InputError naming the file; any other
/// exception, a crash, a sanitizer report, a hang or an allocation beyond libFuzzer's
/// -rss_limit_mb is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit::fuzz {

/// Writes `data` to this process' scratch file ending in `extension` (".obj") and
/// returns its path.
inline std::filesystem::path scratch_file(const std::uint8_t* data, std::size_t size,
                                          const std::string& extension) {
  const char* tmp = std::getenv("TMPDIR");
  const std::filesystem::path path =
      std::filesystem::path(tmp ? tmp : "/tmp") /
      ("tightfit_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// The input as text (JSON readers).
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Runs `read`; an InputError is the reader's correct answer to bad input.
template <typename Read>
int expect_result_or_input_error(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace tightfit::fuzz
