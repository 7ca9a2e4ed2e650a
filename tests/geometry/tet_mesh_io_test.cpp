#include "tightfit/geometry/tet_mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "corrupted_file.hpp"
#include "scratch_dir.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::tet_mesh_io_test {

using test::geometry_data;
using test::ScratchDir;

/// A cube [0, 1/3]^3 split into 6 positive tets around the diagonal 0-6, with a
/// vertex order and coordinates that do not print exactly.
TetMesh cube_tets() {
  TetMesh m;
  m.vertices.resize(8, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  m.vertices /= 3.0;
  m.tets.resize(6, 4);
  m.tets << 0, 1, 2, 6, 0, 2, 3, 6, 0, 3, 7, 6, 0, 7, 4, 6, 0, 4, 5, 6, 0, 5, 1, 6;
  return m;
}

std::vector<MeshField> point_fields(const TetMesh& m) {
  MatX displacement = m.vertices * 0.1;
  displacement.col(2).array() -= 1e-3 / 7.0;
  return {{"pinned", VecX::LinSpaced(m.num_vertices(), 0.0, 1.0)}, {"displacement", displacement}};
}

TEST(TetMeshIo, VtuRoundTrip) {
  ScratchDir dir;
  const TetMesh m = cube_tets();
  const auto pf = point_fields(m);
  const std::vector<MeshField> cf = {{"volume & \"quality\"", VecX::LinSpaced(6, 0.5, 1.0 / 3.0)}};
  write_vtu(dir / "c.vtu", m, pf, cf);
  const VtuData r = read_vtu(dir / "c.vtu");
  EXPECT_EQ(r.mesh.vertices, m.vertices);
  EXPECT_EQ(r.mesh.tets, m.tets);
  ASSERT_EQ(r.point_fields.size(), 2u);
  EXPECT_EQ(r.point_fields[1].name, "displacement");
  EXPECT_EQ(r.point_fields[1].values, pf[1].values);
  ASSERT_EQ(r.cell_fields.size(), 1u);
  EXPECT_EQ(r.cell_fields[0].name, cf[0].name);
  EXPECT_EQ(r.cell_fields[0].values, cf[0].values);
  EXPECT_THROW(write_vtu(dir / "d.vtu", m, {{"short", VecX::Zero(3)}}), std::invalid_argument);
}

TEST(TetMeshIo, VtuIsReadableByMeshio) {
  if (std::system("/usr/bin/python3 -c 'import meshio' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-meshio is not installed";
  ScratchDir dir;
  const TetMesh m = cube_tets();
  write_vtu(dir / "c.vtu", m, point_fields(m), {{"id", VecX::LinSpaced(6, 0, 5)}});
  const auto out = dir / "meshio.txt";
  const std::string script =
      "import meshio, sys\n"
      "m = meshio.read(sys.argv[1])\n"
      "t = m.cells_dict['tetra']\n"
      "print(len(m.points), len(t), m.point_data['displacement'].shape[1], "
      "float(m.cell_data['id'][0].sum()), int(t[5][2]))\n";
  std::ofstream(dir / "check.py") << script;
  const std::string cmd = "/usr/bin/python3 " + (dir / "check.py").string() + " " +
                          (dir / "c.vtu").string() + " > " + out.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(out);
  int points = 0, tets = 0, components = 0, corner = 0;
  double id_sum = 0;
  in >> points >> tets >> components >> id_sum >> corner;
  EXPECT_EQ(points, 8);
  EXPECT_EQ(tets, 6);
  EXPECT_EQ(components, 3);
  EXPECT_EQ(id_sum, 15.0);
  EXPECT_EQ(corner, 1);
}

TEST(TetMeshIo, ReadsVtuFromMeshio) {
  if (std::system("/usr/bin/python3 -c 'import meshio' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-meshio is not installed";
  ScratchDir dir;
  const std::string script =
      "import meshio, numpy as np, sys\n"
      "p = np.array([[0,0,0],[1,0,0],[0,1,0],[0,0,1.5]])\n"
      "m = meshio.Mesh(p, [('tetra', np.array([[0,1,2,3]]))], point_data={'T': np.arange(4.0)})\n"
      "meshio.write(sys.argv[1], m, binary=False)\n";
  std::ofstream(dir / "make.py") << script;
  const std::string cmd =
      "/usr/bin/python3 " + (dir / "make.py").string() + " " + (dir / "m.vtu").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const VtuData r = read_vtu(dir / "m.vtu");
  EXPECT_EQ(r.mesh.num_vertices(), 4);
  ASSERT_EQ(r.mesh.num_tets(), 1);
  EXPECT_EQ(r.mesh.vertices(3, 2), 1.5);
  ASSERT_EQ(r.point_fields.size(), 1u);
  EXPECT_EQ(r.point_fields[0].values(3, 0), 3.0);
}

TEST(TetMeshIo, TetgenRoundTripAndOneBasedInput) {
  ScratchDir dir;
  const TetMesh m = cube_tets();
  write_tetgen(dir / "cube.node", m);
  EXPECT_TRUE(std::filesystem::exists(dir / "cube.ele"));
  const TetMesh r = read_tetgen(dir / "cube");
  EXPECT_EQ(r.vertices, m.vertices);
  EXPECT_EQ(r.tets, m.tets);

  const TetMesh v = read_tetgen(geometry_data("tet_valid.ele"));
  EXPECT_EQ(v.num_vertices(), 5);
  ASSERT_EQ(v.num_tets(), 2);
  EXPECT_EQ(v.tets.row(1), Eigen::RowVector4i(1, 4, 2, 3));
}

TEST(TetMeshIo, ReaderErrorsNameFileAndProblem) {
  try {
    read_tetgen(geometry_data("tet_bad_index"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("tet_bad_index.ele"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 3: node index 9 is out of range"), std::string::npos) << msg;
  }
  ScratchDir dir;
  std::ofstream(dir / "binary.vtu")
      << "<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid><Piece NumberOfPoints=\"1\" "
         "NumberOfCells=\"0\"><Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"binary\">AAAA</DataArray></Points></Piece></UnstructuredGrid></VTKFile>\n";
  try {
    read_vtu(dir / "binary.vtu");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("binary.vtu: line 3: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("only ascii .vtu files are supported"), std::string::npos) << msg;
  }
}

TEST(TetMeshIo, CorruptedFilesGiveOnlyInputErrors) {
  ScratchDir dir;
  const TetMesh m = cube_tets();
  write_vtu(dir / "c.vtu", m, point_fields(m));
  write_tetgen(dir / "t", m);
  test::expect_only_input_errors(
      dir / "c.vtu", 200, [](const auto& p) { read_vtu(p); }, ".vtu");
  // Corrupt the .node file; the reader pairs it with the intact .ele of the same base.
  for (int trial = 0; trial < 100; ++trial) {
    std::filesystem::copy_file(dir / "t.ele", dir / ("corrupt" + std::to_string(trial) + ".ele"));
  }
  test::expect_only_input_errors(
      dir / "t.node", 100, [](const auto& p) { read_tetgen(p); }, ".node");
  test::expect_only_input_errors(
      dir / "t.ele", 100,
      [&](const auto& p) {
        std::filesystem::copy_file(dir / "t.node",
                                   std::filesystem::path(p).replace_extension(".node"),
                                   std::filesystem::copy_options::overwrite_existing);
        read_tetgen(p);
      },
      ".ele");
}

}  // namespace tightfit::tet_mesh_io_test
