// Runs the built `tightfit body` command (TIGHTFIT_CLI).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"

namespace tightfit::body_cli_test {

namespace fs = std::filesystem;

using test::CliRun;
using test::run_cli;

class BodyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_body_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write_spec(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

TEST_F(BodyCli, SpecFileWritesSurfaceVolumeAndSummary) {
  const fs::path spec = write_spec(
      "sphere.json",
      R"({"generator": "sphere", "radius": 0.05, "edge_length": 0.01, "core": {"soft_tissue": 0.01}})");
  const fs::path out = dir_ / "out";
  const CliRun r = run_cli("body " + spec.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find((out / "volume.vtu").string()), std::string::npos);
  const TriMesh surface = read_tri_mesh(out / "surface.obj");
  const VtuData volume = read_vtu(out / "volume.vtu");
  EXPECT_EQ(volume.mesh.vertices.topRows(surface.num_vertices()), surface.vertices);
  ASSERT_EQ(volume.point_fields.size(), 2u);
  EXPECT_EQ(volume.point_fields[0].name, "pinned");
  ASSERT_EQ(volume.cell_fields.size(), 2u);
  EXPECT_EQ(volume.cell_fields[0].name, "volume");
  EXPECT_EQ(volume.cell_fields[1].name, "min_dihedral");
  std::ifstream in(out / "body.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["counts"]["tets"].get<int>(), volume.mesh.num_tets());
  EXPECT_EQ(summary["counts"]["pinned_vertices"].get<int>(),
            static_cast<int>(volume.point_fields[0].values.sum()));
  EXPECT_GT(summary["tets"]["min_dihedral"].get<double>(), 0.0);
  EXPECT_TRUE(summary["timings"].contains("tetrahedralize"));
  // Nothing but the three outputs and tightfit's folder marker (no staging folder).
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 4);
  EXPECT_TRUE(fs::exists(out / ".tightfit"));
}

TEST_F(BodyCli, FlagsWithoutSpec) {
  const fs::path out = dir_ / "flags";
  const CliRun r = run_cli(
      "body --generator cylinder --radius 0.03 --length 0.06 --edge-length 0.01 --soft-tissue=0.01 "
      "--out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "body.json"));
}

TEST_F(BodyCli, MeshFlagIsRelativeToTheCurrentFolder) {
  const fs::path out = dir_ / "head";
  const CliRun r = run_cli(
      "body --mesh bodies/mh_head_neutral.obj --edge-length 0.02 --soft-tissue=0.02 --out " +
          out.string(),
      TIGHTFIT_DATA_DIR);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "body.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["input"]["vertices"].get<int>(), 4426);
  EXPECT_GT(summary["counts"]["pinned_vertices"].get<int>(), 0);
}

TEST_F(BodyCli, BadSpecExitsWithTwoNamingTheFileAndWritesNothing) {
  const fs::path spec =
      write_spec("bad.json", R"({"generator": "cylinder", "radius": "wide", "length": 0.1})");
  const fs::path out = dir_ / "out";
  const CliRun r = run_cli("body " + spec.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(spec.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/radius"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));

  const fs::path thick = write_spec(
      "thick.json",
      R"({"generator": "sphere", "radius": 0.02, "edge_length": 0.01, "core": {"soft_tissue": 0.03}})");
  const CliRun r2 = run_cli("body " + thick.string() + " --out " + out.string());
  EXPECT_EQ(r2.exit_code, 2) << r2.output;
  EXPECT_NE(r2.output.find(thick.string()), std::string::npos) << r2.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace tightfit::body_cli_test
