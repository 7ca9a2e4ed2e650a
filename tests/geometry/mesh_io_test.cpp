#include "tightfit/geometry/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "corrupted_file.hpp"
#include "scratch_dir.hpp"
#include "test_meshes.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::mesh_io_test {

using test::geometry_data;
using test::ScratchDir;

/// A closed mesh with coordinates that are not exact in decimal or float32.
TriMesh awkward_icosahedron() {
  TriMesh m = test::icosahedron();
  m.vertices *= 0.123456789012345;
  m.vertices.col(0).array() += 1.0 / 3.0;
  return m;
}

void expect_same(const TriMesh& a, const TriMesh& b, double tol) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_LE((a.vertices - b.vertices).cwiseAbs().maxCoeff(), tol);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(MeshIo, TextFormatsRoundTripExactly) {
  ScratchDir dir;
  const TriMesh m = awkward_icosahedron();
  for (const char* name : {"a.obj", "a.off", "a.PLY"}) {
    write_tri_mesh(dir / name, m);
    expect_same(read_tri_mesh(dir / name), m, 0.0);
  }
  write_ply(dir / "ascii.ply", m, PlyAttributes{}, PlyEncoding::ascii);
  expect_same(read_tri_mesh(dir / "ascii.ply"), m, 0.0);
}

TEST(MeshIo, StlRoundTripToFloatPrecisionAndWelds) {
  ScratchDir dir;
  const TriMesh m = awkward_icosahedron();
  write_tri_mesh(dir / "a.stl", m);
  EXPECT_EQ(std::filesystem::file_size(dir / "a.stl"), 84u + 50u * 20u);
  const TriMesh r = read_tri_mesh(dir / "a.stl");
  ASSERT_EQ(r.num_vertices(), 12);  // welded
  ASSERT_EQ(r.num_faces(), 20);
  for (int f = 0; f < 20; ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_LE((r.vertices.row(r.faces(f, k)) - m.vertices.row(m.faces(f, k))).norm(), 1e-7);
}

TEST(MeshIo, ReadsAsciiStlAndOff) {
  const TriMesh stl = read_tri_mesh(geometry_data("tet_ascii.stl"));
  EXPECT_EQ(stl.num_vertices(), 4);
  EXPECT_EQ(stl.num_faces(), 4);
  const TriMesh off = read_tri_mesh(geometry_data("tet.off"));
  EXPECT_EQ(off.num_vertices(), 4);
  EXPECT_EQ(off.num_faces(), 4);
  EXPECT_EQ(off.faces.row(3), Eigen::RowVector3i(1, 2, 3));
  // Same corner positions face by face.
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(stl.vertices.row(stl.faces(f, k)), off.vertices.row(off.faces(f, k)));
}

TEST(MeshIo, PlyFieldsAndColorsRoundTrip) {
  ScratchDir dir;
  const TriMesh m = awkward_icosahedron();
  PlyAttributes attr;
  attr.face_fields.push_back({"pressure", VecX::LinSpaced(20, -1.5, 7.25)});
  MatX stretch(20, 2);
  stretch.col(0) = VecX::LinSpaced(20, 1.0, 1.3);
  stretch.col(1) = VecX::LinSpaced(20, 0.9, 1.1);
  attr.face_fields.push_back({"stretch", stretch});
  attr.vertex_fields.push_back({"depth", VecX::LinSpaced(12, 0.0, 1.0 / 7.0)});
  attr.vertex_colors.resize(12, 3);
  for (int i = 0; i < 12; ++i) attr.vertex_colors.row(i) << 20 * i, 255 - 20 * i, 7;
  for (auto enc : {PlyEncoding::ascii, PlyEncoding::binary_little_endian}) {
    write_ply(dir / "f.ply", m, attr, enc);
    const PlyData r = read_ply(dir / "f.ply");
    expect_same(r.mesh, m, 0.0);
    ASSERT_EQ(r.attributes.face_fields.size(), 3u);
    EXPECT_EQ(r.attributes.face_fields[0].name, "pressure");
    EXPECT_EQ(r.attributes.face_fields[0].values, attr.face_fields[0].values);
    EXPECT_EQ(r.attributes.face_fields[1].name, "stretch_0");
    EXPECT_EQ(r.attributes.face_fields[2].name, "stretch_1");
    EXPECT_EQ(r.attributes.face_fields[2].values, stretch.col(1));
    ASSERT_EQ(r.attributes.vertex_fields.size(), 1u);
    EXPECT_EQ(r.attributes.vertex_fields[0].values, attr.vertex_fields[0].values);
    EXPECT_EQ(r.attributes.vertex_colors, attr.vertex_colors);
  }
  // The garment-output overload.
  write_ply(dir / "g.ply", m, {{"stretch", VecX::Constant(20, 1.3)}}, attr.vertex_colors);
  const PlyData g = read_ply(dir / "g.ply");
  ASSERT_EQ(g.attributes.face_fields.size(), 1u);
  EXPECT_EQ(g.attributes.vertex_colors, attr.vertex_colors);
  EXPECT_THROW(write_ply(dir / "h.ply", m, {{"bad name", VecX::Zero(20)}}), std::invalid_argument);
  EXPECT_THROW(write_ply(dir / "h.ply", m, {{"short", VecX::Zero(19)}}), std::invalid_argument);
}

TEST(MeshIo, ReadsBigEndianPlyWithPolygonsAndExtraElements) {
  const PlyData r = read_ply(geometry_data("quad_big_endian.ply"));
  ASSERT_EQ(r.mesh.num_vertices(), 4);
  ASSERT_EQ(r.mesh.num_faces(), 2);
  EXPECT_EQ(r.mesh.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(r.mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(r.mesh.vertices.row(2), Eigen::RowVector3d(1, 1, 0));
  ASSERT_EQ(r.attributes.face_fields.size(), 1u);
  EXPECT_EQ(r.attributes.face_fields[0].values, Eigen::Vector2d(2.5, 2.5));
  ASSERT_EQ(r.attributes.vertex_colors.rows(), 4);
  EXPECT_EQ(r.attributes.vertex_colors(3, 2), 90);
  const TriMesh a = read_tri_mesh(geometry_data("quad_ascii.ply"));
  EXPECT_EQ(a.faces, r.mesh.faces);
  EXPECT_EQ(a.vertices, r.mesh.vertices);
}

TEST(MeshIo, ObjGroupsFromBlenderStyleFile) {
  const ObjGroups g = read_obj_with_groups(geometry_data("groups.obj"));
  EXPECT_EQ(g.mesh.num_vertices(), 6);
  ASSERT_EQ(g.mesh.num_faces(), 6);
  EXPECT_EQ(g.group_names, (std::vector<std::string>{"front", "back"}));
  EXPECT_EQ(g.face_group, (std::vector<int>{0, 0, 1, 1, 1, 0}));
  EXPECT_EQ(g.mesh.faces.row(2), Eigen::RowVector3i(1, 4, 5));  // negative indices
  EXPECT_EQ(g.mesh.faces.row(3), Eigen::RowVector3i(1, 4, 5));  // quad fan 2 5 6 3
  EXPECT_EQ(g.mesh.faces.row(4), Eigen::RowVector3i(1, 5, 2));

  ScratchDir dir;
  write_obj_with_groups(dir / "g.obj", g);
  const ObjGroups r = read_obj_with_groups(dir / "g.obj");
  expect_same(r.mesh, g.mesh, 0.0);
  EXPECT_EQ(r.group_names, g.group_names);
  EXPECT_EQ(r.face_group, g.face_group);
}

TEST(MeshIo, ReadsTriangleBody) {
  const TriMesh m = read_tri_mesh(TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj");
  EXPECT_EQ(m.num_vertices(), 3838);
  EXPECT_EQ(m.num_faces(), 7672);
}

TEST(MeshIo, ReadsQuadBodyAsTriangles) {
  const TriMesh m = read_tri_mesh(TIGHTFIT_DATA_DIR "/bodies/mh_male_regular.obj");
  EXPECT_EQ(m.num_faces(), 26756);
}

TEST(MeshIo, ReaderErrorsNameFileAndProblem) {
  struct Case {
    const char* file;
    const char* expected;
  };
  const Case cases[] = {
      {"bad_number.obj", "line 3: vertex coordinate 'x' is not a number"},
      {"short_face.obj", "line 3: face needs at least 3 vertices"},
      {"bad_index.obj", "line 7: face vertex index 9 is out of range (the file has 4 vertices)"},
      {"negative_index.obj", "relative face index -7 points before the first vertex"},
      {"bad_index.ply", "face 0 refers to vertex 5, the file has 3 vertices"},
      {"truncated.ply", "the element counts in the header are larger than the file can hold"},
      {"truncated_list.ply", "the file ends inside the data of face 0"},
      {"bad_count.off", "the file ends after 1 of 2 faces"},
      {"no_such_file.obj", "file does not exist"},
  };
  for (const auto& c : cases) {
    const auto path = geometry_data(c.file);
    const std::string msg = error_of([&] { read_tri_mesh(path); });
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expected), std::string::npos) << msg;
  }
  EXPECT_NE(error_of([] { read_tri_mesh("mesh.xyz"); }).find("unknown surface mesh format '.xyz'"),
            std::string::npos);
}

TEST(MeshIo, WritersAreAtomic) {
  ScratchDir dir;
  // Writing into a missing directory fails and leaves nothing behind.
  EXPECT_THROW(write_tri_mesh(dir / "missing/a.obj", test::cube()), InputError);
  write_tri_mesh(dir / "a.obj", test::cube());
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  EXPECT_EQ(files, 1);
}

TEST(MeshIo, CorruptedFilesGiveOnlyInputErrors) {
  ScratchDir dir;
  const TriMesh m = awkward_icosahedron();
  PlyAttributes attr;
  attr.face_fields.push_back({"pressure", VecX::LinSpaced(20, 0.0, 1.0)});
  write_ply(dir / "a.ply", m, attr, PlyEncoding::ascii);
  write_ply(dir / "b.ply", m, attr, PlyEncoding::binary_little_endian);
  write_obj(dir / "c.obj", m);
  write_off(dir / "d.off", m);
  write_stl(dir / "e.stl", m);
  auto read = [](const std::filesystem::path& p) { read_tri_mesh(p); };
  for (const char* name : {"a.ply", "b.ply", "c.obj", "d.off", "e.stl"})
    test::expect_only_input_errors(dir / name, 200, read,
                                   std::filesystem::path(name).extension().string());
  test::expect_only_input_errors(geometry_data("tet_ascii.stl"), 100, read, ".stl");
  test::expect_only_input_errors(geometry_data("quad_big_endian.ply"), 100, read, ".ply");
}

}  // namespace tightfit::mesh_io_test
