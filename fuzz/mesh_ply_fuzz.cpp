/// libFuzzer target: the PLY reader (ASCII and binary of both byte orders).
#include "fuzz_input.hpp"
#include "tightfit/geometry/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tightfit::fuzz::scratch_file(data, size, ".ply");
  return tightfit::fuzz::expect_result_or_input_error([&] { tightfit::read_ply(path); });
}
