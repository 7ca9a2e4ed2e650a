#include "tightfit/geometry/mesh_io.hpp"

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {
[[noreturn]] void unknown_format(const std::filesystem::path& path) {
  throw InputError(path.string(), "unknown surface mesh format '" + path.extension().string() +
                                      "' (expected .obj, .ply, .off or .stl)");
}
}  // namespace

TriMesh read_tri_mesh(const std::filesystem::path& path) {
  const std::string ext = text::lower_extension(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".ply") return read_ply(path).mesh;
  if (ext == ".off") return read_off(path);
  if (ext == ".stl") return read_stl(path);
  unknown_format(path);
}

void write_tri_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  const std::string ext = text::lower_extension(path);
  if (ext == ".obj") return write_obj(path, mesh);
  if (ext == ".ply") return write_ply(path, mesh);
  if (ext == ".off") return write_off(path, mesh);
  if (ext == ".stl") return write_stl(path, mesh);
  unknown_format(path);
}

}  // namespace tightfit
