/// OBJ reader and writer (see mesh_io.hpp).
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

/// Parses the vertex index of one `f` token ("7", "7/2", "7//3", "-1/2/3") into a
/// 0-based index. Positive indices are checked against the final vertex count later.
int parse_face_index(std::string_view token, std::int64_t num_vertices_so_far,
                     const std::string& source, int line) {
  const std::string_view first = token.substr(0, token.find('/'));
  const auto value = text::to_int(first);
  if (!value)
    throw InputError(source, text::at_line(line) + "face corner '" + std::string(token) +
                                 "' does not start with a vertex index");
  if (*value == 0)
    throw InputError(source, text::at_line(line) + "face vertex index 0 (OBJ indices start at 1)");
  std::int64_t index = *value > 0 ? *value - 1 : num_vertices_so_far + *value;
  if (index < 0)
    throw InputError(source, text::at_line(line) + "relative face index " + std::to_string(*value) +
                                 " points before the first vertex (" +
                                 std::to_string(num_vertices_so_far) + " vertices so far)");
  if (index > std::numeric_limits<int>::max())
    throw InputError(
        source, text::at_line(line) + "face index " + std::to_string(*value) + " is too large");
  return static_cast<int>(index);
}

ObjGroups parse_obj(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string data = text::read_file(path);
  text::LineCursor cursor(data);

  std::vector<double> coords;
  std::vector<int> corners;     // 3 per triangle
  std::vector<int> face_lines;  // source line of each triangle (for range errors)
  std::vector<int> face_group;
  std::vector<std::string> group_names;
  std::unordered_map<std::string, int> group_index;
  std::string current_group = "default";
  int current_group_id = -1;  // resolved lazily so unused groups are not listed

  std::vector<std::string_view> tokens;
  std::vector<int> polygon;
  std::string joined;  // a logical line made of several physical lines ending in '\'
  while (auto physical = cursor.next()) {
    std::string_view line = *physical;
    const int line_no = cursor.line_number();
    if (!line.empty() && line.back() == '\\') {
      joined.append(line.substr(0, line.size() - 1));
      joined.push_back(' ');
      continue;
    }
    if (!joined.empty()) {
      joined.append(line);
      line = joined;
    }
    text::split(text::strip_comment(line), tokens);
    if (!tokens.empty()) {
      const std::string_view key = tokens[0];
      if (key == "v") {
        if (tokens.size() < 4)
          throw InputError(source, text::at_line(line_no) + "vertex needs 3 coordinates, found " +
                                       std::to_string(tokens.size() - 1));
        for (int k = 1; k <= 3; ++k) {
          const auto value = text::to_double(tokens[k]);
          if (!value)
            throw InputError(source, text::at_line(line_no) + "vertex coordinate '" +
                                         std::string(tokens[k]) + "' is not a number");
          coords.push_back(*value);
        }
      } else if (key == "f" || key == "fo") {
        if (tokens.size() < 4)
          throw InputError(source, text::at_line(line_no) +
                                       "face needs at least 3 vertices, found " +
                                       std::to_string(tokens.size() - 1));
        const auto nv = static_cast<std::int64_t>(coords.size() / 3);
        polygon.clear();
        for (std::size_t k = 1; k < tokens.size(); ++k)
          polygon.push_back(parse_face_index(tokens[k], nv, source, line_no));
        if (current_group_id < 0) {
          auto [it, inserted] =
              group_index.emplace(current_group, static_cast<int>(group_names.size()));
          if (inserted) group_names.push_back(current_group);
          current_group_id = it->second;
        }
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
          corners.insert(corners.end(), {polygon[0], polygon[k], polygon[k + 1]});
          face_lines.push_back(line_no);
          face_group.push_back(current_group_id);
        }
      } else if (key == "g" || key == "o") {
        const std::string_view content = text::strip_comment(line);
        const std::string_view rest = text::trim(content.substr(content.find(key) + key.size()));
        current_group = rest.empty() ? std::string("default") : std::string(rest);
        current_group_id = -1;
      }
      // Everything else (vt, vn, vp, s, l, p, mtllib, usemtl, ...) does not affect
      // the triangle mesh.
    }
    joined.clear();
  }

  ObjGroups out;
  const int nv = static_cast<int>(coords.size() / 3);
  out.mesh.vertices = Eigen::Map<const Points3>(coords.data(), nv, 3);
  const int nf = static_cast<int>(corners.size() / 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (corners[3 * f + k] >= nv)
        throw InputError(source, text::at_line(face_lines[f]) + "face vertex index " +
                                     std::to_string(corners[3 * f + k] + 1) +
                                     " is out of range (the file has " + std::to_string(nv) +
                                     " vertices)");
  out.mesh.faces = Eigen::Map<const Triangles>(corners.data(), nf, 3);
  out.face_group = std::move(face_group);
  out.group_names = std::move(group_names);
  return out;
}

void write_vertices(std::ostream& out, const TriMesh& mesh) {
  for (int i = 0; i < mesh.num_vertices(); ++i)
    out << "v " << text::format_double(mesh.vertices(i, 0)) << ' '
        << text::format_double(mesh.vertices(i, 1)) << ' '
        << text::format_double(mesh.vertices(i, 2)) << '\n';
}

void write_face(std::ostream& out, const TriMesh& mesh, int f) {
  out << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1
      << '\n';
}

}  // namespace

TriMesh read_obj(const std::filesystem::path& path) { return parse_obj(path).mesh; }

ObjGroups read_obj_with_groups(const std::filesystem::path& path) { return parse_obj(path); }

void write_obj(const std::filesystem::path& path, const TriMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    require_finite_matrix(mesh.vertices, "the vertex positions");
    out << "# tightfit triangle mesh: " << mesh.num_vertices() << " vertices, " << mesh.num_faces()
        << " faces\n";
    write_vertices(out, mesh);
    for (int f = 0; f < mesh.num_faces(); ++f) write_face(out, mesh, f);
  });
}

void write_obj_with_groups(const std::filesystem::path& path, const ObjGroups& groups) {
  const TriMesh& mesh = groups.mesh;
  if (static_cast<int>(groups.face_group.size()) != mesh.num_faces())
    throw std::invalid_argument("write_obj_with_groups: one group per face required");
  const int ng = static_cast<int>(groups.group_names.size());
  for (int g : groups.face_group)
    if (g < 0 || g >= ng) throw std::invalid_argument("write_obj_with_groups: bad group index");
  for (const auto& name : groups.group_names)
    if (name.find_first_of("\r\n") != std::string::npos)
      throw std::invalid_argument("write_obj_with_groups: group name with a line break");
  write_file_atomically(path, [&](std::ostream& out) {
    require_finite_matrix(mesh.vertices, "the vertex positions");
    out << "# tightfit triangle mesh with " << ng << " groups\n";
    write_vertices(out, mesh);
    int current = -1;
    for (int f = 0; f < mesh.num_faces(); ++f) {
      if (groups.face_group[f] != current) {
        current = groups.face_group[f];
        out << "g " << groups.group_names[current] << '\n';
      }
      write_face(out, mesh, f);
    }
  });
}

}  // namespace tightfit
