/// OFF reader and writer (see mesh_io.hpp).
#include <ostream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

TriMesh read_off(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string data = text::read_file(path);
  text::LineCursor cursor(data);
  std::vector<std::string_view> tokens;

  // Next non-empty line (comments removed) split into `tokens`; false at the end.
  auto next_tokens = [&]() {
    while (auto line = cursor.next()) {
      text::split(text::strip_comment(*line), tokens);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  auto fail = [&](const std::string& what) -> InputError {
    return InputError(source, text::at_line(cursor.line_number()) + what);
  };

  if (!next_tokens() || tokens[0] != "OFF")
    throw InputError(source, "not an OFF file (the first line must be 'OFF')");
  // Counts may follow the keyword on the same line.
  std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
  if (counts.empty()) {
    if (!next_tokens()) throw fail("the file ends before the vertex and face counts");
    counts = tokens;
  }
  if (counts.size() < 2) throw fail("expected 'VERTICES FACES [EDGES]' counts");
  const auto nv = text::to_int(counts[0]);
  const auto nf = text::to_int(counts[1]);
  if (!nv || !nf || *nv < 0 || *nf < 0) throw fail("bad vertex or face count");
  // Every record takes at least two bytes: reject counts the file cannot hold before
  // allocating for them.
  const auto max_records = static_cast<std::int64_t>(data.size() / 2);
  if (*nv > max_records || *nf > max_records)
    throw fail("vertex or face count larger than the file can hold");

  TriMesh mesh;
  mesh.vertices.resize(*nv, 3);
  for (std::int64_t i = 0; i < *nv; ++i) {
    if (!next_tokens())
      throw fail("the file ends after " + std::to_string(i) + " of " + std::to_string(*nv) +
                 " vertices");
    if (tokens.size() < 3) throw fail("vertex needs 3 coordinates");
    for (int d = 0; d < 3; ++d) {
      const auto value = text::to_double(tokens[d]);
      if (!value) throw fail("vertex coordinate '" + std::string(tokens[d]) + "' is not a number");
      mesh.vertices(i, d) = *value;
    }
  }
  std::vector<int> corners;
  std::vector<int> polygon;
  for (std::int64_t f = 0; f < *nf; ++f) {
    if (!next_tokens())
      throw fail("the file ends after " + std::to_string(f) + " of " + std::to_string(*nf) +
                 " faces");
    const auto n = text::to_int(tokens[0]);
    if (!n || *n < 3) throw fail("face needs a vertex count of at least 3");
    if (static_cast<std::int64_t>(tokens.size()) < 1 + *n)
      throw fail("face has fewer indices than its count " + std::to_string(*n));
    polygon.clear();
    for (std::int64_t k = 1; k <= *n; ++k) {
      const auto index = text::to_int(tokens[k]);
      if (!index) throw fail("face index '" + std::string(tokens[k]) + "' is not an integer");
      if (*index < 0 || *index >= *nv)
        throw fail("face index " + std::to_string(*index) + " is out of range (the file has " +
                   std::to_string(*nv) + " vertices)");
      polygon.push_back(static_cast<int>(*index));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      corners.insert(corners.end(), {polygon[0], polygon[k], polygon[k + 1]});
  }
  mesh.faces = Eigen::Map<const Triangles>(corners.data(), static_cast<int>(corners.size() / 3), 3);
  return mesh;
}

void write_off(const std::filesystem::path& path, const TriMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    require_finite_matrix(mesh.vertices, "the vertex positions");
    out << "OFF\n" << mesh.num_vertices() << ' ' << mesh.num_faces() << " 0\n";
    for (int i = 0; i < mesh.num_vertices(); ++i)
      out << text::format_double(mesh.vertices(i, 0)) << ' '
          << text::format_double(mesh.vertices(i, 1)) << ' '
          << text::format_double(mesh.vertices(i, 2)) << '\n';
    for (int f = 0; f < mesh.num_faces(); ++f)
      out << "3 " << mesh.faces(f, 0) << ' ' << mesh.faces(f, 1) << ' ' << mesh.faces(f, 2) << '\n';
  });
}

}  // namespace tightfit
