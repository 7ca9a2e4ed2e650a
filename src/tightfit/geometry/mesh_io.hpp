#pragma once
/// Reading and writing triangle surface meshes: OBJ, PLY, OFF, STL.
///
/// Readers return vertices as stored (no unit conversion) and split polygons into
/// triangle fans (v0, vi, vi+1). Every reader error is an InputError whose source is
/// the file and whose message says what is wrong, with the line number for text files.
/// Readers do not validate topology or geometry: use mesh_validation.hpp for that.
/// Writers are atomic (temporary file + rename) and write numbers so that they read
/// back exactly (text formats use the shortest round-trip decimal form).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// Reads a triangle mesh, choosing the format from the extension (.obj, .ply, .off,
/// .stl; case-insensitive).
TriMesh read_tri_mesh(const std::filesystem::path& path);
/// Writes a triangle mesh, choosing the format from the extension: OBJ and OFF as
/// text, PLY as binary little endian, STL as binary (float32; vertices are not shared).
void write_tri_mesh(const std::filesystem::path& path, const TriMesh& mesh);

// ---- OBJ -------------------------------------------------------------------------

/// An OBJ mesh with the group of each face: the name from the latest `g` or `o`
/// line before the face ("default" for faces before any such line). Groups are
/// numbered in order of first use.
struct ObjGroups {
  TriMesh mesh;
  std::vector<int> face_group;           ///< one entry per triangle, index into `group_names`
  std::vector<std::string> group_names;  ///< distinct names in order of first use
};

/// Reads `v` and `f` lines (f with `a`, `a/b`, `a//c`, `a/b/c` forms; negative
/// indices count back from the latest vertex); ignores vt, vn, s, l, p, mtllib,
/// usemtl and other statements. A `v` line with more than 3 numbers (w or colour) uses
/// the first three.
TriMesh read_obj(const std::filesystem::path& path);
/// Like read_obj, also returning the face groups (for garment layouts from Blender).
ObjGroups read_obj_with_groups(const std::filesystem::path& path);
/// Writes `v` and `f` lines.
void write_obj(const std::filesystem::path& path, const TriMesh& mesh);
/// Writes `v` lines, then the faces in order with a `g NAME` line wherever the group
/// changes, so read_obj_with_groups gives the same faces and groups back (groups
/// without faces are not stored). Group names must not contain line breaks and
/// `face_group` must have one valid entry per face (std::invalid_argument otherwise).
void write_obj_with_groups(const std::filesystem::path& path, const ObjGroups& groups);

// ---- PLY -------------------------------------------------------------------------

/// A named quantity per element: one row per element (vertex, face or tet), one
/// column per component (1 for a scalar, 3 for a vector).
struct MeshField {
  std::string name;
  MatX values;
};

/// 8-bit RGB colour per vertex, n×3 (or empty for none).
using VertexColors = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Extra per-element data stored in a PLY file besides positions and faces.
struct PlyAttributes {
  std::vector<MeshField> vertex_fields;  ///< written as double properties of "vertex"
  std::vector<MeshField> face_fields;    ///< written as double properties of "face"
  VertexColors vertex_colors;            ///< written as uchar red, green, blue
};

/// A PLY mesh with its scalar properties other than x, y, z, the face index list and
/// red/green/blue (which fill `vertex_colors` when all three are present).
/// Every property becomes a one-column field; face fields are repeated for each
/// triangle of a split polygon.
struct PlyData {
  TriMesh mesh;
  PlyAttributes attributes;
};

/// The enumerators are PLY's own format keywords.
enum class PlyEncoding { ascii, binary_little_endian };  // NOLINT(readability-identifier-naming)

/// Reads ascii, binary_little_endian and binary_big_endian PLY with a "vertex"
/// element (x, y, z of any numeric type) and a "face" element (list property
/// vertex_indices or vertex_index). Other elements are skipped.
PlyData read_ply(const std::filesystem::path& path);
/// Writes positions (double), faces (uchar count, int indices) and the attributes.
/// A field with k > 1 columns is written as properties NAME_0 .. NAME_{k-1}.
/// Field names must be non-empty without blanks and rows must match the element
/// counts (std::invalid_argument otherwise).
void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               const PlyAttributes& attributes = {},
               PlyEncoding encoding = PlyEncoding::binary_little_endian);
/// Garment output: per-face fields (e.g. stretch, pressure) and optional vertex colours.
void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               const std::vector<MeshField>& face_fields, const VertexColors& vertex_colors = {},
               PlyEncoding encoding = PlyEncoding::binary_little_endian);

// ---- OFF -------------------------------------------------------------------------

/// Reads OFF ("OFF" header, counts, vertices, faces as `n i0 .. in-1`; trailing face
/// colours and `#` comments are ignored).
TriMesh read_off(const std::filesystem::path& path);
void write_off(const std::filesystem::path& path, const TriMesh& mesh);

// ---- STL -------------------------------------------------------------------------

/// Reads ascii or binary STL (binary when the size matches 84 + 50·count). Corners
/// with equal coordinates are welded into one vertex, numbered in order of first
/// appearance.
TriMesh read_stl(const std::filesystem::path& path);
/// Writes binary STL (float32, facet normals from the geometry).
void write_stl(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace tightfit
