#pragma once
/// Reading and writing tetrahedral meshes: VTK XML UnstructuredGrid (.vtu, ascii) for
/// ParaView/meshio, and TetGen .node/.ele. Errors are InputError naming the file and
/// what is wrong; writers are atomic. Tet corner order is kept as stored (use
/// validate_tet_mesh to check orientation).
#include <filesystem>
#include <vector>

#include "tightfit/geometry/mesh.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit {

/// Writes an ascii .vtu with one piece: points (Float64), tetrahedral cells (VTK type
/// 10), and the given fields as PointData / CellData (Float64, NumberOfComponents =
/// columns). Point fields need one row per vertex, cell fields one row per tet, names
/// non-empty (std::invalid_argument otherwise).
void write_vtu(const std::filesystem::path& path, const TetMesh& mesh,
               const std::vector<MeshField>& point_fields = {},
               const std::vector<MeshField>& cell_fields = {});

/// A tet mesh read from a .vtu file with its point and cell data arrays.
struct VtuData {
  TetMesh mesh;
  std::vector<MeshField> point_fields;
  std::vector<MeshField> cell_fields;
};

/// Reads an ascii .vtu UnstructuredGrid with a single piece whose cells are all
/// tetrahedra (VTK type 10). Binary and appended data arrays are rejected with an
/// InputError that says so.
VtuData read_vtu(const std::filesystem::path& path);

/// Reads TetGen `BASE.node` and `BASE.ele`. `path` may be BASE, BASE.node or BASE.ele.
/// Node numbering may start at 0 or 1 (taken from the first node); attributes and
/// boundary markers are ignored; for 10-node tets the 4 corners are kept.
TetMesh read_tetgen(const std::filesystem::path& path);

/// Writes `BASE.node` and `BASE.ele` (0-based numbering, no attributes or markers).
/// `path` may be BASE, BASE.node or BASE.ele.
void write_tetgen(const std::filesystem::path& path, const TetMesh& mesh);

}  // namespace tightfit
