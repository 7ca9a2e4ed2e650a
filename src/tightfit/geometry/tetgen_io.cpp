/// TetGen .node/.ele reader and writer (see tet_mesh_io.hpp).
#include <ostream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

std::filesystem::path base_of(const std::filesystem::path& path) {
  const std::string ext = text::lower_extension(path);
  if (ext == ".node" || ext == ".ele") {
    auto base = path;
    base.replace_extension();
    return base;
  }
  return path;
}

std::filesystem::path with_suffix(const std::filesystem::path& base, const char* suffix) {
  auto p = base;
  p += suffix;
  return p;
}

/// Non-empty, comment-free lines of a TetGen file, split into tokens, with errors
/// naming the file and line.
class TetgenFile {
 public:
  explicit TetgenFile(const std::filesystem::path& path)
      : source_(path.string()), data_(text::read_file(path)), cursor_(data_) {}

  /// Reads the next record into tokens(); throws `what_missing` at the end of the file.
  void next(const std::string& what_missing) {
    while (auto line = cursor_.next()) {
      text::split(text::strip_comment(*line), tokens_);
      if (!tokens_.empty()) return;
    }
    throw InputError(source_, "the file ends before " + what_missing);
  }
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  /// Upper bound on the number of records (each takes at least two bytes).
  std::int64_t max_records() const { return static_cast<std::int64_t>(data_.size() / 2); }

  std::int64_t integer(std::size_t k, const char* what) const {
    const auto value = k < tokens_.size() ? text::to_int(tokens_[k]) : std::nullopt;
    if (!value) throw error(std::string("expected an integer ") + what);
    return *value;
  }
  double number(std::size_t k, const char* what) const {
    const auto value = k < tokens_.size() ? text::to_double(tokens_[k]) : std::nullopt;
    if (!value) throw error(std::string("expected a number ") + what);
    return *value;
  }
  InputError error(const std::string& what) const {
    return InputError(source_, text::at_line(cursor_.line_number()) + what);
  }

 private:
  std::string source_;
  std::string data_;
  text::LineCursor cursor_;
  std::vector<std::string_view> tokens_;
};

}  // namespace

TetMesh read_tetgen(const std::filesystem::path& path) {
  const auto base = base_of(path);
  TetMesh mesh;
  std::int64_t first_index = 0;
  {
    TetgenFile node(with_suffix(base, ".node"));
    node.next("the header line");
    const auto n = node.integer(0, "point count");
    const auto dim = node.tokens().size() > 1 ? node.integer(1, "dimension") : 3;
    if (n < 0 || n > node.max_records()) throw node.error("bad point count " + std::to_string(n));
    if (dim != 3) throw node.error("dimension " + std::to_string(dim) + ", expected 3");
    mesh.vertices.resize(n, 3);
    for (std::int64_t i = 0; i < n; ++i) {
      node.next("point " + std::to_string(i) + " of " + std::to_string(n));
      const auto index = node.integer(0, "point index");
      if (i == 0) {
        if (index != 0 && index != 1) throw node.error("the first point index must be 0 or 1");
        first_index = index;
      }
      if (index != first_index + i)
        throw node.error("point index " + std::to_string(index) + ", expected " +
                         std::to_string(first_index + i));
      for (int d = 0; d < 3; ++d) mesh.vertices(i, d) = node.number(1 + d, "coordinate");
    }
  }
  TetgenFile ele(with_suffix(base, ".ele"));
  ele.next("the header line");
  const auto m = ele.integer(0, "tetrahedron count");
  const auto per = ele.tokens().size() > 1 ? ele.integer(1, "nodes per tetrahedron") : 4;
  if (m < 0 || m > ele.max_records()) throw ele.error("bad tetrahedron count " + std::to_string(m));
  if (per != 4 && per != 10) throw ele.error("nodes per tetrahedron must be 4 or 10");
  mesh.tets.resize(m, 4);
  const auto nv = static_cast<std::int64_t>(mesh.vertices.rows());
  for (std::int64_t t = 0; t < m; ++t) {
    ele.next("tetrahedron " + std::to_string(t) + " of " + std::to_string(m));
    if (static_cast<std::int64_t>(ele.tokens().size()) < 1 + per)
      throw ele.error("tetrahedron needs " + std::to_string(per) + " node indices");
    for (int c = 0; c < 4; ++c) {
      const auto v = ele.integer(1 + c, "node index") - first_index;
      if (v < 0 || v >= nv)
        throw ele.error("node index " + std::to_string(v + first_index) +
                        " is out of range (the .node file has " + std::to_string(nv) + " points)");
      mesh.tets(t, c) = static_cast<int>(v);
    }
  }
  return mesh;
}

void write_tetgen(const std::filesystem::path& path, const TetMesh& mesh) {
  const auto base = base_of(path);
  write_file_atomically(with_suffix(base, ".node"), [&](std::ostream& out) {
    require_finite_matrix(mesh.vertices, "the node positions");
    out << mesh.num_vertices() << " 3 0 0\n";
    for (int i = 0; i < mesh.num_vertices(); ++i)
      out << i << ' ' << text::format_double(mesh.vertices(i, 0)) << ' '
          << text::format_double(mesh.vertices(i, 1)) << ' '
          << text::format_double(mesh.vertices(i, 2)) << '\n';
    out << "# written by tightfit\n";
  });
  write_file_atomically(with_suffix(base, ".ele"), [&](std::ostream& out) {
    out << mesh.num_tets() << " 4 0\n";
    for (int t = 0; t < mesh.num_tets(); ++t)
      out << t << ' ' << mesh.tets(t, 0) << ' ' << mesh.tets(t, 1) << ' ' << mesh.tets(t, 2) << ' '
          << mesh.tets(t, 3) << '\n';
    out << "# written by tightfit\n";
  });
}

}  // namespace tightfit
