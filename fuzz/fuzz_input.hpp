#pragma once
/// The libFuzzer entry point of one reader (fuzz/*_fuzz.cpp, `make fuzz`).
///
/// tightfit's readers take file paths, so each input is written to a scratch file with
/// the reader's extension (in TMPDIR, one per process) and read back. The contract
/// under test: a reader either succeeds or throws InputError naming the file; any other
/// exception, a crash, a sanitizer report, a hang or an allocation beyond libFuzzer's
/// -rss_limit_mb is a finding.
#include <cstdint>
#include <cstdlib>

#include "readers.hpp"
#include "tightfit/common/error.hpp"

/// Defines LLVMFuzzerTestOneInput for the reader called `name` (readers.hpp).
#define TIGHTFIT_FUZZ_READER(name)                                                        \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {     \
    static const tightfit::fuzz::Reader& reader = tightfit::fuzz::readers().at(name);     \
    const char* tmp = std::getenv("TMPDIR");                                              \
    static const std::filesystem::path path =                                             \
        std::filesystem::path(tmp ? tmp : "/tmp") /                                       \
        ("tightfit_fuzz_" + std::to_string(::getpid()) + reader.extension);               \
    {                                                                                     \
      std::ofstream out(path, std::ios::binary | std::ios::trunc);                        \
      out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size)); \
    }                                                                                     \
    try {                                                                                 \
      reader.read(path);                                                                  \
    } catch (const tightfit::InputError&) {                                               \
    }                                                                                     \
    return 0;                                                                             \
  }
