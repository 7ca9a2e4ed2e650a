/// The PLY files of a simulate run (garment.ply, body.ply) as Debian's meshio reads them.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "report/support/fit_test_tools.hpp"
#include "report/support/fit_test_view.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::simulate_ply_test {

/// Reads `ply` with Debian's python3-meshio and returns its JSON dump.
nlohmann::json read_with_meshio(const std::filesystem::path& ply, const test::TempDir& dir) {
  const auto out = dir / (ply.stem().string() + "_meshio.json");
  const auto result = test::run_command(
      "/usr/bin/python3 " + test::shell_quote(test::source_path("tests/report/fit_ply_read.py")) +
          " " + test::shell_quote(ply) + " " + test::shell_quote(out),
      dir / "meshio.log");
  EXPECT_EQ(result.exit_code, 0) << "meshio could not read " << ply << " (needs /usr/bin/python3 "
                                 << "with python3-meshio, see scripts/install-deps.sh):\n"
                                 << result.output;
  std::ifstream in(out);
  if (!in) return nlohmann::json();
  return nlohmann::json::parse(in);
}

void expect_mesh_and_fields(const nlohmann::json& read, const TriMesh& mesh,
                            const std::vector<FaceField>& fields) {
  ASSERT_TRUE(read.is_object());
  ASSERT_EQ(read["points"].size(), static_cast<std::size_t>(mesh.num_vertices()));
  ASSERT_EQ(read["triangles"].size(), static_cast<std::size_t>(mesh.num_faces()));
  for (int v = 0; v < mesh.num_vertices(); v += 7) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(read["points"][v][k].get<double>(), mesh.vertices(v, k));
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) ASSERT_EQ(read["triangles"][f][k].get<int>(), mesh.faces(f, k));
  }
  const auto& data = read["cell_data"];
  std::size_t columns = 0;
  for (const auto& field : fields) {
    for (int c = 0; c < field.components(); ++c) {
      const std::string name =
          field.components() == 1 ? field.name : field.name + "_" + std::to_string(c);
      ++columns;
      ASSERT_TRUE(data.contains(name)) << "meshio did not find face property " << name;
      ASSERT_EQ(data[name].size(), static_cast<std::size_t>(mesh.num_faces()));
      for (int f = 0; f < mesh.num_faces(); ++f) {
        ASSERT_EQ(data[name][f].get<double>(), field.values(f, c)) << name << " face " << f;
      }
    }
  }
  EXPECT_EQ(data.size(), columns);
}

TEST(FitPly, MeshioReadsTheFieldsOfASimulateRun) {
  // The files `tightfit simulate` writes (garment.ply, body.ply), read by meshio: every
  // face property equals what our own PLY reader finds (both read the same numbers).
  test::TempDir dir("ply_cli");
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                           "hoop_scale": 0.9, "axial_scale": 0.95, "edge_length": 0.016,
                           "pin_first_ring": true, "pin_last_ring": true}},
    "body_material": {"rigid": true}})";
  const auto run = test::run_command(std::string(TIGHTFIT_CLI) + " simulate " +
                                         test::shell_quote(dir / "scene.json") + " --out " +
                                         test::shell_quote(dir / "run"),
                                     dir / "simulate.log");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* file : {"garment.ply", "body.ply"}) {
    const PlyData ours = read_ply(dir / "run" / file);
    std::vector<FaceField> fields;
    for (const MeshField& f : ours.attributes.face_fields) fields.push_back({f.name, "", f.values});
    const auto read = read_with_meshio(dir / "run" / file, dir);
    expect_mesh_and_fields(read, ours.mesh, fields);
    if (std::string(file) == "garment.ply") {
      for (const char* name :
           {"stretch_max", "stretch_min", "regime", "pressure_pa", "pressure_mmhg"})
        EXPECT_TRUE(read["cell_data"].contains(name)) << name;
    }
  }
}

}  // namespace tightfit::simulate_ply_test
