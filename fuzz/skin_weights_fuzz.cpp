/// libFuzzer target: MakeHuman skin-weight files (.mhw) for a fixed small mesh (a
/// tetrahedron's surface, 4 vertices).
#include "fuzz_input.hpp"
#include "tightfit/body/skin_weights.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path mesh = [] {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
    const char* tmp = std::getenv("TMPDIR");
    const auto path = std::filesystem::path(tmp ? tmp : "/tmp") /
                      ("tightfit_fuzz_mesh_" + std::to_string(::getpid()) + ".obj");
    std::ofstream(path) << obj;
    return path;
  }();
  const auto path = tightfit::fuzz::scratch_file(data, size, ".mhw");
  return tightfit::fuzz::expect_result_or_input_error([&] { tightfit::read_skin_weights(mesh, path); });
}
