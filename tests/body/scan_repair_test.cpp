#include "tightfit/body/scan_repair.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_run.hpp"
#include "support/sphere_mesh.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/body/scan_import.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit::scan_repair_test {

TriMesh legs_body() {
  return read_tri_mesh(std::filesystem::path(TIGHTFIT_DATA_DIR) / "bodies/mh_legs_male.obj");
}

/// `mesh` without the faces that have a corner for which `drop` is true.
template <class Drop>
TriMesh without_faces(const TriMesh& mesh, Drop drop) {
  TriMesh out;
  out.vertices = mesh.vertices;
  out.faces.resize(mesh.num_faces(), 3);
  int kept = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    bool keep = true;
    for (int c = 0; c < 3; ++c) keep = keep && !drop(Vec3(mesh.vertices.row(mesh.faces(f, c))));
    if (keep) out.faces.row(kept++) = mesh.faces.row(f);
  }
  out.faces.conservativeResize(kept, 3);
  return out;
}

/// Every face with its own three vertices (an STL file), plus a copy of face 0 and a
/// face with a repeated corner.
TriMesh as_soup(const TriMesh& mesh) {
  TriMesh out;
  const int m = mesh.num_faces();
  out.vertices.resize(3 * m, 3);
  out.faces.resize(m + 2, 3);
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      out.vertices.row(3 * f + c) = mesh.vertices.row(mesh.faces(f, c));
      out.faces(f, c) = 3 * f + c;
    }
  out.faces.row(m) << 2, 1, 0;
  out.faces.row(m + 1) << 3, 4, 3;
  return out;
}

std::string input_error(const auto& run) {
  try {
    run();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ScanRepair, ACleanMeshPassesUnchanged) {
  const TriMesh body = legs_body();
  std::vector<std::string> warnings;
  const TriMesh imported = import_scan(body, "legs.obj", 0.0, warnings);
  EXPECT_EQ(imported.vertices, body.vertices);
  EXPECT_EQ(imported.faces, body.faces);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(ScanRepair, APunchedHoleIsFilledAndTheBodyKeepsItsVolume) {
  const TriMesh body = legs_body();
  // A hole of two rings of faces on the front of the left thigh.
  int front = -1;
  for (int v = 0; v < body.num_vertices(); ++v)
    if (body.vertices(v, 0) > 0.0 && std::abs(body.vertices(v, 1) - 0.7) < 0.05 &&
        (front < 0 || body.vertices(v, 2) > body.vertices(front, 2)))
      front = v;
  ASSERT_GE(front, 0);
  const Vec3 center = body.vertices.row(front);
  const TriMesh punched =
      without_faces(body, [&](const Vec3& p) { return (p - center).norm() < 0.02; });
  ASSERT_LT(punched.num_faces(), body.num_faces() - 5);
  std::vector<std::string> warnings;
  const TriMesh filled = import_scan(punched, "scan.obj", 1.0, warnings);
  // Closed, manifold, outward, without self-intersections.
  const std::vector<std::string> problems = surface_problems(filled);
  EXPECT_TRUE(problems.empty()) << problems.front();
  EXPECT_NEAR(signed_volume(filled) / signed_volume(body), 1.0, 1e-3);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(contains(warnings[0], "scan.obj: filled 1 hole(s) of the surface (boundary 0."))
      << warnings[0];
  EXPECT_TRUE(contains(warnings[0], " m, ")) << warnings[0];
  const FilledSurface direct = fill_small_holes(punched, "scan.obj");
  ASSERT_EQ(direct.filled.size(), 1u);
  EXPECT_GT(direct.filled[0].boundary_length, 0.08);
  EXPECT_LT(direct.filled[0].boundary_length, direct.hole_limit);
  EXPECT_LT((direct.filled[0].center - center).norm(), 0.02);
}

TEST(ScanRepair, AFilledHoleIsRefinedAndFaired) {
  // A hole of 2 cm radius at the top of a ball of 0.2 m with 8 mm edges: the patch gets
  // vertices inside, faired onto the sphere's curvature, much closer to it than a flat
  // patch through the rim (its centre is that far off).
  const double radius = 0.2;
  const TriMesh sphere = test::sphere_mesh(radius, Vec3::Zero(), 0.008);
  int top = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.vertices(v, 2) > sphere.vertices(top, 2)) top = v;
  const Vec3 pole = sphere.vertices.row(top);
  const TriMesh punched =
      without_faces(sphere, [&](const Vec3& p) { return (p - pole).norm() < 0.02; });
  const FilledSurface filled = fill_small_holes(punched, "ball.obj");
  ASSERT_EQ(filled.filled.size(), 1u);
  EXPECT_TRUE(filled.filled[0].faired);
  EXPECT_TRUE(filled.unfilled.empty());
  ASSERT_GT(filled.mesh.num_vertices(), punched.num_vertices() + 3);
  const double flat = radius - filled.filled[0].center.norm();
  double farthest = 0.0;
  for (int v = punched.num_vertices(); v < filled.mesh.num_vertices(); ++v)
    farthest = std::max(farthest, std::abs(Vec3(filled.mesh.vertices.row(v)).norm() - radius));
  EXPECT_GT(flat, 5e-4);
  EXPECT_LT(farthest, 0.2 * flat) << "flat patch " << flat;
  EXPECT_NEAR(filled.enclosed_volume, signed_volume(sphere), 1e-4 * signed_volume(sphere));
}

TEST(ScanRepair, DuplicateVerticesAndFacesAreMerged) {
  const TriMesh sphere = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  std::vector<std::string> warnings;
  const TriMesh repaired = repair_mesh_elements(as_soup(sphere), "scan.stl", warnings);
  EXPECT_EQ(repaired.num_vertices(), sphere.num_vertices());
  EXPECT_EQ(repaired.num_faces(), sphere.num_faces());
  EXPECT_NEAR(signed_volume(repaired), signed_volume(sphere), 1e-12);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(
      contains(warnings[0], "scan.stl: repaired the mesh: " +
                                std::to_string(3 * sphere.num_faces() - sphere.num_vertices()) +
                                " duplicate vertices merged, 2 duplicate faces"))
      << warnings[0];
  warnings.clear();
  EXPECT_EQ(repair_mesh_elements(sphere, "x", warnings).num_faces(), sphere.num_faces());
  EXPECT_TRUE(warnings.empty());
}

TEST(ScanRepair, NonManifoldVertexIsSplitAndTheLargerPartKept) {
  // Two balls touching at one shared vertex (the small one's bottom on the big one's top).
  const TriMesh big = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  int top = 0;
  for (int v = 0; v < big.num_vertices(); ++v)
    if (big.vertices(v, 2) > big.vertices(top, 2)) top = v;
  TriMesh small = test::sphere_mesh(0.03, Vec3::Zero(), 0.01);
  int bottom = 0;
  for (int v = 0; v < small.num_vertices(); ++v)
    if (small.vertices(v, 2) < small.vertices(bottom, 2)) bottom = v;
  small.vertices.rowwise() += big.vertices.row(top) - small.vertices.row(bottom);
  TriMesh touching;
  touching.vertices.resize(big.num_vertices() + small.num_vertices(), 3);
  touching.vertices << big.vertices, small.vertices;
  touching.faces.resize(big.num_faces() + small.num_faces(), 3);
  touching.faces << big.faces, (small.faces.array() + big.num_vertices()).matrix();
  for (int f = big.num_faces(); f < touching.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (touching.faces(f, c) == big.num_vertices() + bottom) touching.faces(f, c) = top;
  ASSERT_FALSE(surface_problems(touching, {.allow_isolated_vertices = true}).empty());
  std::vector<std::string> warnings;
  const TriMesh kept = import_scan(touching, "scan.ply", 1.0, warnings);
  EXPECT_TRUE(surface_problems(kept).empty());
  EXPECT_EQ(kept.num_faces(), big.num_faces());
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_TRUE(contains(warnings[0], "1 non-manifold vertices split")) << warnings[0];
  EXPECT_TRUE(contains(warnings[1], "2 separate parts")) << warnings[1];
}

TEST(ScanRepair, NonManifoldEdgeIsCutAndItsFinLeftOut) {
  // A third face on an edge of the ball: a fin sticking out.
  const TriMesh sphere = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  TriMesh fin = sphere;
  const int a = sphere.faces(0, 0), b = sphere.faces(0, 1);
  const Vec3 tip = 0.5 * (sphere.vertices.row(a) + sphere.vertices.row(b)) * 1.3;
  fin.vertices.conservativeResize(sphere.num_vertices() + 1, 3);
  fin.vertices.row(sphere.num_vertices()) = tip;
  fin.faces.conservativeResize(sphere.num_faces() + 1, 3);
  fin.faces.row(sphere.num_faces()) << a, b, sphere.num_vertices();
  std::vector<std::string> warnings;
  const TriMesh kept = import_scan(fin, "scan.obj", 1.0, warnings);
  EXPECT_TRUE(surface_problems(kept).empty());
  EXPECT_NEAR(signed_volume(kept), signed_volume(sphere), 1e-3 * signed_volume(sphere));
  ASSERT_FALSE(warnings.empty());
  EXPECT_TRUE(contains(warnings[0], "1 non-manifold edges cut open")) << warnings[0];
}

TEST(ScanRepair, UnrepairableInputsNameTheFile) {
  TriMesh pinched = test::sphere_mesh(0.1, Vec3::Zero(), 0.03);
  pinched.faces.col(1) = pinched.faces.col(0);  // every face has a repeated corner
  std::vector<std::string> warnings;
  std::string message = input_error([&] { import_scan(pinched, "scan.obj", 0.0, warnings); });
  EXPECT_TRUE(contains(message, "scan.obj: no face is left after removing duplicate faces"))
      << message;
  TriMesh broken = test::sphere_mesh(0.1, Vec3::Zero(), 0.03);
  broken.vertices(3, 1) = std::nan("");
  message = input_error([&] { import_scan(broken, "scan.obj", 0.0, warnings); });
  EXPECT_TRUE(contains(message, "scan.obj: vertex 3 has a coordinate that is not a finite number"))
      << message;
}

TEST(ScanRepair, AHoleTooLargeToFillIsAnError) {
  // Legs open at the waist: 0.9 m around, against a limit of 0.25 m for 0.98 m² of skin.
  const TriMesh open = without_faces(legs_body(), [](const Vec3& p) { return p.y() > 1.0; });
  std::vector<std::string> warnings;
  const std::string message = input_error([&] { import_scan(open, "legs.obj", 0.0, warnings); });
  EXPECT_TRUE(contains(message,
                       "legs.obj: the body's surface is open: 1 hole(s) too large to fill, "
                       "the largest with boundary 0."))
      << message;
  EXPECT_TRUE(contains(message, "holes are filled up to a boundary of 0.2")) << message;
  // A small ball whose top third is missing: no closed part is kept in its place.
  const TriMesh cap = without_faces(test::sphere_mesh(0.1, Vec3::Zero(), 0.02),
                                    [](const Vec3& p) { return p.z() > 0.05; });
  EXPECT_THROW(import_scan(cap, "x", 0.0, warnings), InputError);
}

TEST(ScanRepair, InsideOutSurfaceIsTurned) {
  TriMesh sphere = test::sphere_mesh(0.1, Vec3::Zero(), 0.03);
  const double volume = signed_volume(sphere);
  sphere.faces.col(1).swap(sphere.faces.col(2));
  std::vector<std::string> warnings;
  const TriMesh turned = import_scan(sphere, "x", 1.0, warnings);
  EXPECT_NEAR(signed_volume(turned), volume, 1e-12);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(contains(warnings[0], "turned them outwards")) << warnings[0];
}

TEST(ScanRepair, BodyCommandRepairsAScan) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tightfit_scan_repair_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // A ball of 0.2 m without the faces around its top vertex.
  const TriMesh sphere = test::sphere_mesh(0.2, Vec3::Zero(), 0.02);
  int top = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.vertices(v, 2) > sphere.vertices(top, 2)) top = v;
  const Vec3 pole = sphere.vertices.row(top);
  write_tri_mesh(
      dir / "scan.obj",
      as_soup(without_faces(sphere, [&](const Vec3& p) { return (p - pole).norm() < 1e-9; })));
  const test::CliRun r = test::run_cli("body --mesh " + (dir / "scan.obj").string() +
                                       " --edge-length 0.03 --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "warning: " + (dir / "scan.obj").string() + ": repaired the mesh"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "filled 1 hole(s)")) << r.output;
  EXPECT_TRUE(contains(test::read_text(dir / "out" / "body.json"), "filled 1 hole(s)"));
  std::filesystem::remove_all(dir);
}

}  // namespace tightfit::scan_repair_test
