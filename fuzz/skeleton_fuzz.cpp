/// libFuzzer target: MakeHuman joints files (data/rig/*.joints.json).
#include "fuzz_input.hpp"
#include "tightfit/body/skeleton.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tightfit::fuzz::scratch_file(data, size, ".json");
  return tightfit::fuzz::expect_result_or_input_error([&] { tightfit::read_skeleton(path); });
}
