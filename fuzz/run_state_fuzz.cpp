/// libFuzzer target: a run's state.json (read by `tightfit export`).
#include "fuzz_input.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/io/run_state.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return tightfit::fuzz::expect_result_or_input_error([&] {
    const nlohmann::json doc = tightfit::parse_json_text(tightfit::fuzz::text(data, size), "state.json");
    tightfit::run_state_from_json(doc, "state.json");
  });
}
