/// Every mesh writer refuses a NaN or infinity in positions or fields: a SolverError
/// naming the file and the array, row and column, and no file (not even a temporary).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scratch_dir.hpp"
#include "test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"

namespace tightfit::finite_mesh_writers_test {

namespace fs = std::filesystem;

constexpr double kMeshNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMeshInf = std::numeric_limits<double>::infinity();

/// The message of the SolverError `write` throws ("" and a failure when none).
std::string mesh_writer_error(const std::function<void()>& write) {
  try {
    write();
  } catch (const SolverError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SolverError";
  return {};
}

bool no_file_in(const fs::path& dir) {
  return fs::directory_iterator(dir) == fs::directory_iterator();
}

TEST(FiniteMeshWriters, SurfaceWritersRefuseANonFinitePosition) {
  test::ScratchDir dir;
  TriMesh mesh = test::cube();
  mesh.vertices(5, 2) = kMeshNaN;
  for (const std::string name : {"a.ply", "b.obj", "c.off", "d.stl"}) {
    const fs::path file = dir / name;
    const std::string what = mesh_writer_error([&] { write_tri_mesh(file, mesh); });
    EXPECT_NE(what.find(file.string() + ": not written: non-finite number (nan) in the vertex "
                                        "positions, row 5, column 2"),
              std::string::npos)
        << what;
  }
  ObjGroups groups{mesh, std::vector<int>(static_cast<size_t>(mesh.num_faces()), 0), {"all"}};
  EXPECT_NE(mesh_writer_error([&] { write_obj_with_groups(dir / "g.obj", groups); }).find("row 5"),
            std::string::npos);
  EXPECT_TRUE(no_file_in(dir.path()));
}

TEST(FiniteMeshWriters, PlyRefusesANonFiniteFaceOrVertexField) {
  test::ScratchDir dir;
  const TriMesh mesh = test::cube();
  VecX pressure = VecX::Constant(mesh.num_faces(), 1200.0);
  pressure[7] = kMeshInf;
  std::string what = mesh_writer_error([&] {
    write_ply(dir / "garment.ply", mesh, {{"pressure_pa", pressure}}, {}, PlyEncoding::ascii);
  });
  EXPECT_NE(what.find("garment.ply: not written: non-finite number (inf) in the face field "
                      "'pressure_pa', row 7, column 0"),
            std::string::npos)
      << what;
  PlyAttributes attributes;
  attributes.vertex_fields.push_back({"force", MatX::Zero(mesh.num_vertices(), 3)});
  attributes.vertex_fields.back().values(2, 1) = -kMeshInf;
  what = mesh_writer_error([&] { write_ply(dir / "body.ply", mesh, attributes); });
  EXPECT_NE(what.find("(-inf) in the vertex field 'force', row 2, column 1"), std::string::npos)
      << what;
  EXPECT_TRUE(no_file_in(dir.path()));
}

TEST(FiniteMeshWriters, VolumeWritersRefuseANonFinitePositionOrField) {
  test::ScratchDir dir;
  TetMesh mesh;
  mesh.vertices = Points3::Identity(4, 3);
  mesh.vertices.row(3).setZero();
  mesh.tets = Tetrahedra(1, 4);
  mesh.tets << 0, 1, 2, 3;
  MatX displacement = MatX::Zero(4, 3);
  displacement(1, 0) = kMeshNaN;
  std::string what = mesh_writer_error([&] {
    write_vtu(dir / "a.vtu", mesh, {{"u", displacement}});
  });
  EXPECT_NE(what.find("(nan) in the point field 'u', row 1, column 0"), std::string::npos) << what;
  mesh.vertices(0, 0) = kMeshInf;
  what = mesh_writer_error([&] { write_vtu(dir / "b.vtu", mesh); });
  EXPECT_NE(what.find("(inf) in the point positions, row 0, column 0"), std::string::npos) << what;
  what = mesh_writer_error([&] { write_tetgen(dir / "c.node", mesh); });
  EXPECT_NE(what.find("(inf) in the node positions, row 0"), std::string::npos) << what;
  EXPECT_TRUE(no_file_in(dir.path()));
}

}  // namespace tightfit::finite_mesh_writers_test
