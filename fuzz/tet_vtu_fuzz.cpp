/// libFuzzer target: the VTU (VTK XML unstructured grid) reader of tet meshes.
#include "fuzz_input.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tightfit::fuzz::scratch_file(data, size, ".vtu");
  return tightfit::fuzz::expect_result_or_input_error([&] { tightfit::read_vtu(path); });
}
