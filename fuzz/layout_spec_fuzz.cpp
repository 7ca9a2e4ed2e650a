/// libFuzzer target: layout spec files (cut planes, pieces, seams, pins).
#include "fuzz_input.hpp"
#include "tightfit/garment/layout_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tightfit::fuzz::scratch_file(data, size, ".json");
  return tightfit::fuzz::expect_result_or_input_error([&] { tightfit::read_layout_spec(path.string()); });
}
