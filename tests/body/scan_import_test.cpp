#include "tightfit/body/scan_import.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "support/cli_run.hpp"
#include "support/sphere_mesh.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_components.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit::scan_import_test {

/// `parts` stacked into one mesh.
TriMesh join(const std::vector<TriMesh>& parts) {
  TriMesh out;
  Eigen::Index nv = 0, nf = 0;
  for (const TriMesh& p : parts) {
    nv += p.num_vertices();
    nf += p.num_faces();
  }
  out.vertices.resize(nv, 3);
  out.faces.resize(nf, 3);
  Eigen::Index v = 0, f = 0;
  for (const TriMesh& p : parts) {
    out.vertices.middleRows(v, p.num_vertices()) = p.vertices;
    out.faces.middleRows(f, p.num_faces()) = p.faces.array() + static_cast<int>(v);
    v += p.num_vertices();
    f += p.num_faces();
  }
  return out;
}

TEST(ScanImport, ComponentsAreSplitAndRenumbered) {
  const TriMesh big = test::sphere_mesh(0.1, Vec3::Zero(), 0.03),
                small = test::sphere_mesh(0.02, Vec3(1, 0, 0), 0.01);
  const std::vector<MeshComponent> parts = connected_components(join({small, big}));
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].mesh.num_faces(), std::max(big.num_faces(), small.num_faces()));
  for (const MeshComponent& c : parts) {
    EXPECT_EQ(c.mesh.faces.maxCoeff() + 1, c.mesh.num_vertices());
    EXPECT_NEAR(std::abs(signed_volume(c.mesh)),
                std::abs(signed_volume(c.mesh.num_faces() == big.num_faces() ? big : small)),
                1e-15);
  }
}

TEST(ScanImport, KeepsTheLargestClosedPartWithAWarning) {
  const TriMesh body = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  const TriMesh blob = test::sphere_mesh(0.03, Vec3(0.5, 0, 0), 0.01);
  // An open sheet with more faces than the body: a floor scanned along.
  TriMesh sheet = test::sphere_mesh(0.3, Vec3(0, -2, 0), 0.01);
  sheet.faces.conservativeResize(sheet.num_faces() - 1, 3);
  std::vector<std::string> warnings;
  const TriMesh kept =
      keep_largest_closed_component(join({blob, sheet, body}), "scan.obj", warnings);
  EXPECT_EQ(kept.num_faces(), body.num_faces());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("scan.obj: the mesh has 3 separate parts"), std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("open"), std::string::npos);
  warnings.clear();
  EXPECT_EQ(keep_largest_closed_component(body, "x", warnings).num_faces(), body.num_faces());
  EXPECT_TRUE(warnings.empty());
  TriMesh open_blob = blob;
  open_blob.faces.conservativeResize(open_blob.num_faces() - 1, 3);
  EXPECT_THROW(keep_largest_closed_component(join({open_blob, sheet}), "x", warnings), InputError);
}

TEST(ScanImport, UnitsAreGuessedFromTheBodySize) {
  TriMesh legs =
      read_tri_mesh(std::filesystem::path(TIGHTFIT_DATA_DIR) / "bodies/mh_legs_male.obj");
  std::vector<std::string> warnings;
  EXPECT_EQ(guess_units_to_metres(legs, "legs.obj", warnings), 1.0);
  EXPECT_TRUE(warnings.empty());
  TriMesh mm = legs;
  mm.vertices *= 1000.0;  // 1.1 m tall in millimetres
  EXPECT_EQ(guess_units_to_metres(mm, "legs.obj", warnings), 0.001);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("millimetres"), std::string::npos) << warnings[0];
  TriMesh cm = legs;
  cm.vertices *= 10.0;  // 11 units: centimetres of a 0.11 m part
  EXPECT_EQ(guess_units_to_metres(cm, "x", warnings), 0.01);
  TriMesh ambiguous = legs;
  ambiguous.vertices *= 100.0;  // 110 units: a 1.1 m body in cm or a 0.11 m part in mm
  try {
    guess_units_to_metres(ambiguous, "legs.obj", warnings);
    ADD_FAILURE() << "guessed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"units\""), std::string::npos) << e.what();
  }
  TriMesh huge = legs;
  huge.vertices *= 1e4;
  EXPECT_THROW(guess_units_to_metres(huge, "x", warnings), InputError);
  EXPECT_EQ(metres_per_unit("cm", "x"), 0.01);
  EXPECT_THROW(metres_per_unit("inch", "x"), InputError);
}

TEST(ScanImport, BodyCommandReadsABodyInMillimetres) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tightfit_scan_import_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TriMesh sphere = test::sphere_mesh(0.2, Vec3::Zero(), 0.04);
  sphere.vertices *= 1000.0;  // a 400 mm ball
  write_tri_mesh(dir / "ball_mm.obj", sphere);
  const test::CliRun r = test::run_cli("body --mesh " + (dir / "ball_mm.obj").string() +
                                       " --edge-length 0.03 --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("millimetres"), std::string::npos) << r.output;
  const TriMesh built = read_tri_mesh(dir / "out" / "surface.obj");
  const double extent =
      (built.vertices.colwise().maxCoeff() - built.vertices.colwise().minCoeff()).maxCoeff();
  EXPECT_NEAR(extent, 0.4, 0.02);
  // 200 units is ambiguous (a 2 m body in cm, a 0.2 m part in mm): "units" settles it.
  TriMesh small = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  small.vertices *= 1000.0;
  write_tri_mesh(dir / "small_mm.obj", small);
  const std::string args = "body --mesh " + (dir / "small_mm.obj").string() +
                           " --edge-length 0.02 --out " + (dir / "out2").string();
  test::CliRun s = test::run_cli(args);
  EXPECT_EQ(s.exit_code, 2) << s.output;
  EXPECT_NE(s.output.find("\"units\""), std::string::npos) << s.output;
  s = test::run_cli(args + " --units mm");
  EXPECT_EQ(s.exit_code, 0) << s.output;
  EXPECT_EQ(s.output.find("warning:"), std::string::npos) << s.output;
  std::filesystem::remove_all(dir);
}

}  // namespace tightfit::scan_import_test
