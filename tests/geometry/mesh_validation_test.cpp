#include "tightfit/geometry/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <functional>

#include "scratch_dir.hpp"
#include "test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"

namespace tightfit::mesh_validation_test {

using test::geometry_data;

/// The InputError message of reading and validating a surface file with `req`.
std::string surface_error(const std::string& file, const SurfaceRequirements& req = {}) {
  const auto path = geometry_data(file).string();
  try {
    validate_surface(read_tri_mesh(path), path, req);
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path);
    return e.what();
  }
  return "(valid)";
}

std::string tet_error(const std::string& file) {
  const auto path = geometry_data(file).string();
  try {
    validate_tet_mesh(read_tetgen(path), path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(valid)";
}

struct BadFile {
  const char* file;
  const char* problem;
};

class BadSurfaceFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadSurfaceFile, MessageNamesFileAndProblem) {
  const std::string msg = surface_error(GetParam().file);
  EXPECT_NE(msg.find(geometry_data(GetParam().file).string() + ": "), std::string::npos) << msg;
  EXPECT_NE(msg.find(GetParam().problem), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    Geometry, BadSurfaceFile,
    ::testing::Values(
        BadFile{"nonfinite_vertex.obj", "non-finite vertex coordinates: vertex 0 (nan, 0, 0)"},
        BadFile{"bad_index.obj", "face vertex index 9 is out of range"},
        BadFile{"negative_index.obj", "relative face index -7 points before the first vertex"},
        BadFile{"degenerate_repeated.obj", "degenerate face repeating a vertex: face 4 (1, 1, 2)"},
        BadFile{"degenerate_zero_area.obj", "degenerate face with zero area: face 5 (1, 4, 0)"},
        BadFile{"non_manifold_edge.obj", "non-manifold edge: edge 0-1 has 4 faces"},
        BadFile{"non_manifold_vertex.obj",
                "non-manifold vertex: the faces around vertex 0 form more than one fan"},
        BadFile{"hole.obj", "the surface is not closed: it has a hole: boundary loop of 3 edges"},
        BadFile{"inconsistent_orientation.obj", "3 edges with inconsistent orientation"},
        BadFile{"inward.obj", "inward orientation: the enclosed signed volume is -0.1666"},
        BadFile{"self_intersection.obj", "self-intersecting face pairs: faces "},
        BadFile{"unused_vertex.obj", "unused vertex: vertex 4 is in no face"}),
    [](const auto& param_info) {
      std::string name = param_info.param.file;
      return name.substr(0, name.find('.'));
    });

TEST(SurfaceValidation, OnlyTheIntendedProblemIsReported) {
  // Each bad file has exactly one kind of problem (so the messages above are specific).
  for (const char* file :
       {"nonfinite_vertex.obj", "degenerate_zero_area.obj", "non_manifold_edge.obj",
        "non_manifold_vertex.obj", "hole.obj", "inconsistent_orientation.obj", "inward.obj",
        "self_intersection.obj", "unused_vertex.obj"}) {
    const auto problems = surface_problems(read_tri_mesh(geometry_data(file)));
    EXPECT_EQ(problems.size(), 1u) << file << ": " << ::testing::PrintToString(problems);
  }
}

TEST(SurfaceValidation, ValidMeshesPass) {
  EXPECT_EQ(surface_error("valid_tet.obj"), "(valid)");
  EXPECT_TRUE(surface_problems(test::icosahedron()).empty());
  EXPECT_TRUE(surface_problems(test::cube()).empty());
  // An open strip is fine when a closed surface is not required.
  SurfaceRequirements open;
  open.closed = false;
  EXPECT_TRUE(surface_problems(test::strip(3), open).empty());
  EXPECT_EQ(surface_problems(test::strip(3)).size(), 1u);
  // Unused vertices can be allowed.
  SurfaceRequirements loose;
  loose.allow_isolated_vertices = true;
  EXPECT_EQ(surface_error("unused_vertex.obj", loose), "(valid)");
}

TEST(SurfaceValidation, BadIndicesInMemory) {
  TriMesh m = test::cube();
  m.faces(3, 1) = -2;
  m.faces(7, 2) = 8;
  const auto problems = surface_problems(m);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0],
            "2 faces with bad vertex indices: face 3 (4, -2, 7) has an index outside [0, 8); "
            "face 7 (3, 6, 8) has an index outside [0, 8)");
  EXPECT_EQ(surface_problems(TriMesh{}), std::vector<std::string>{"the mesh has no faces"});
}

TEST(SurfaceValidation, TinyButWellShapedFacesAreNotDegenerate) {
  TriMesh m = test::icosahedron();
  m.vertices *= 1e-9;
  EXPECT_TRUE(surface_problems(m).empty());
}

TEST(SurfaceValidation, BodiesAreValid) {
  for (const char* body : {"mh_legs_male.obj", "mh_male_regular.obj"}) {
    const std::string path = std::string(TIGHTFIT_DATA_DIR "/bodies/") + body;
    EXPECT_NO_THROW(validate_surface(read_tri_mesh(path), path)) << body;
  }
  const std::string legs = TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj";
  const TriMesh legs_mesh = read_tri_mesh(legs);
  EXPECT_NO_THROW(validate_surface(legs_mesh, legs));
  EXPECT_EQ(legs_mesh.num_faces(), 7672);
  const std::string hole = geometry_data("hole.obj").string();
  EXPECT_THROW(validate_surface(read_tri_mesh(hole), hole), InputError);
}

TEST(TetValidation, BadTetFilesNameFileAndProblem) {
  const BadFile cases[] = {
      {"tet_inverted", "inverted tet: tet 1 (1, 2, 4, 3) has volume -0.3333"},
      {"tet_zero_volume", "zero-volume tet: tet 1 (0, 1, 4, 2) has volume 0"},
      {"tet_nonfinite", "non-finite vertex coordinates: vertex 2 (0, inf, 0)"},
      {"tet_bad_index", "node index 9 is out of range"},
  };
  for (const auto& c : cases) {
    const std::string msg = tet_error(c.file);
    EXPECT_NE(msg.find(geometry_data(c.file).string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.problem), std::string::npos) << msg;
  }
  EXPECT_EQ(tet_error("tet_valid"), "(valid)");
}

TEST(TetValidation, InMemoryProblems) {
  TetMesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.tets.resize(3, 4);
  m.tets << 0, 1, 2, 3, 0, 1, 1, 3, 0, 1, 2, 4;
  auto problems = tet_mesh_problems(m);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("tet 2 (0, 1, 2, 4) has an index outside [0, 4)"), std::string::npos);
  m.tets.conservativeResize(2, 4);
  problems = tet_mesh_problems(m);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0], "degenerate tet repeating a vertex: tet 1 (0, 1, 1, 3)");
  EXPECT_EQ(tet_mesh_problems(TetMesh{}),
            std::vector<std::string>{"the tet mesh has no tetrahedra"});
}

}  // namespace tightfit::mesh_validation_test
