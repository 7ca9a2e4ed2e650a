/// libFuzzer target: scene files (JSON text → SceneSpec, with every section's parser).
/// Relative paths resolve against TMPDIR, where nothing of a scene exists.
#include "fuzz_input.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/io/scene_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tightfit::fuzz::scratch_file(data, size, ".json");
  return tightfit::fuzz::expect_result_or_input_error([&] {
    const nlohmann::json doc = tightfit::parse_json_text(tightfit::fuzz::text(data, size), "scene.json");
    tightfit::parse_scene(doc, "scene.json", path.parent_path());
  });
}
