/// libFuzzer target: an optimization's checkpoint.json (read by `--resume`), for an
/// objective with the terms the seed checkpoints have.
#include "fuzz_input.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/design/optimization_checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<std::string> names{"stretch", "seam length", "boundary spacing"};
  return tightfit::fuzz::expect_result_or_input_error([&] {
    const nlohmann::json doc =
        tightfit::parse_json_text(tightfit::fuzz::text(data, size), "checkpoint.json");
    tightfit::checkpoint_from_json(doc, names, "checkpoint.json");
  });
}
