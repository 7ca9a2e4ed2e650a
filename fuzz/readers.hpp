#pragma once
/// The readers under fuzzing, by name: one place that the libFuzzer targets
/// (fuzz/*_fuzz.cpp) and the regression test of their findings
/// (tests/app/fuzz_regression_test.cpp, files in tests/fuzz_regressions/READER/) share.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tightfit/body/bvh.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"
#include "tightfit/patterns/json.hpp"
#include "tightfit/scene/fabric_fit.hpp"
#include "tightfit/scene/fabric_spec.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"
#include "tightfit/scene/run_state.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::fuzz {

/// A reader: its file extension and how to read a file with it.
struct Reader {
  std::string extension;
  std::function<void(const std::filesystem::path&)> read;
};

/// A tetrahedron's surface in the temporary folder, for the skin-weight reader
/// (weights need their mesh).
inline std::filesystem::path small_mesh() {
  const auto path = std::filesystem::temp_directory_path() /
                    ("tightfit_fuzz_mesh_" + std::to_string(::getpid()) + ".obj");
  if (!std::filesystem::exists(path))
    std::ofstream(path)
        << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  return path;
}

/// Every reader by name. JSON documents are read as their commands read them (text →
/// parse_json_text → the document's parser); checkpoints for an objective with the
/// terms "stretch", "seam length", "boundary spacing"; strip tests are read and fitted.
inline const std::map<std::string, Reader>& readers() {
  static const std::map<std::string, Reader> all = {
      {"json", {".json", [](const auto& f) { read_json_file(f.string()); }}},
      {"obj", {".obj", [](const auto& f) { read_obj_with_groups(f); }}},
      {"ply", {".ply", [](const auto& f) { read_ply(f); }}},
      {"off", {".off", [](const auto& f) { read_off(f); }}},
      {"stl", {".stl", [](const auto& f) { read_stl(f); }}},
      {"vtu", {".vtu", [](const auto& f) { read_vtu(f); }}},
      {"scene",
       {".json",
        [](const auto& f) {
          parse_scene(read_json_file(f.string()), f.string(), f.parent_path());
        }}},
      {"state",
       {".json",
        [](const auto& f) { run_state_from_json(read_json_file(f.string()), f.string()); }}},
      {"checkpoint",
       {".json",
        [](const auto& f) {
          static const std::vector<std::string> names{"stretch", "seam length", "boundary spacing"};
          checkpoint_from_json(read_json_file(f.string()), names, f.string());
        }}},
      {"pieces", {".json", [](const auto& f) { read_pieces_json(f); }}},
      {"skeleton", {".json", [](const auto& f) { read_skeleton(f); }}},
      {"skin_weights", {".mhw", [](const auto& f) { read_skin_weights(small_mesh(), f); }}},
      {"layout", {".json", [](const auto& f) { read_layout_spec(f.string()); }}},
      {"bvh", {".bvh", [](const auto& f) { read_bvh(f); }}},
      {"fabric", {".json", [](const auto& f) { read_fabric_file(f); }}},
      {"strip_csv",
       {".csv",
        [](const auto& f) {
          FabricFitOptions options;
          options.shear_n_per_m = 30.0;
          options.files = f.string();
          fit_fabric(read_strip_test_csv(f), options);
        }}},
  };
  return all;
}

}  // namespace tightfit::fuzz
