/// STL reader and writer (see mesh_io.hpp).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <ostream>

#include <Eigen/Geometry>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

/// Welds corners with equal coordinates, numbering vertices by first appearance.
/// Corners with a NaN coordinate are never welded (validation reports them).
class Welder {
 public:
  int add(double x, double y, double z) {
    if (std::isnan(x) || std::isnan(y) || std::isnan(z)) {
      coords_.insert(coords_.end(), {x, y, z});
      return count_++;
    }
    const auto [it, inserted] = index_.emplace(std::array<double, 3>{x, y, z}, count_);
    if (inserted) {
      coords_.insert(coords_.end(), {x, y, z});
      ++count_;
    }
    return it->second;
  }
  Points3 vertices() const { return Eigen::Map<const Points3>(coords_.data(), count_, 3); }

 private:
  std::map<std::array<double, 3>, int> index_;
  std::vector<double> coords_;
  int count_ = 0;
};

template <class T>
T load_le(const char* p) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <class T>
void put_le(std::ostream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.write(bytes, sizeof(T));
}

TriMesh read_binary_stl(const std::string& data, std::uint32_t count) {
  Welder welder;
  std::vector<int> corners;
  corners.reserve(3 * static_cast<std::size_t>(count));
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* p = data.data() + 84 + 50 * static_cast<std::size_t>(t) + 12;  // skip normal
    for (int c = 0; c < 3; ++c) {
      const double x = load_le<float>(p + 12 * c);
      const double y = load_le<float>(p + 12 * c + 4);
      const double z = load_le<float>(p + 12 * c + 8);
      corners.push_back(welder.add(x, y, z));
    }
  }
  TriMesh mesh;
  mesh.vertices = welder.vertices();
  mesh.faces = Eigen::Map<const Triangles>(corners.data(), static_cast<int>(count), 3);
  return mesh;
}

TriMesh read_ascii_stl(const std::string& source, const std::string& data) {
  text::LineCursor cursor(data);
  std::vector<std::string_view> tokens;
  Welder welder;
  std::vector<int> corners;
  int in_facet = -1;  // vertices read in the current facet, -1 outside a facet
  bool solid = false;
  while (auto line = cursor.next()) {
    text::split(*line, tokens);
    if (tokens.empty()) continue;
    const auto fail = [&](const std::string& what) {
      return InputError(source, text::at_line(cursor.line_number()) + what);
    };
    const std::string_view key = tokens[0];
    if (key == "solid") {
      solid = true;
    } else if (key == "facet") {
      if (in_facet >= 0) throw fail("'facet' inside a facet");
      in_facet = 0;
    } else if (key == "vertex") {
      if (in_facet < 0) throw fail("'vertex' outside a facet");
      if (in_facet == 3) throw fail("a facet with more than 3 vertices");
      if (tokens.size() != 4) throw fail("vertex needs 3 coordinates");
      double xyz[3];
      for (int d = 0; d < 3; ++d) {
        const auto value = text::to_double(tokens[d + 1]);
        if (!value)
          throw fail("vertex coordinate '" + std::string(tokens[d + 1]) + "' is not a number");
        xyz[d] = *value;
      }
      corners.push_back(welder.add(xyz[0], xyz[1], xyz[2]));
      ++in_facet;
    } else if (key == "endfacet") {
      if (in_facet != 3) throw fail("a facet must have exactly 3 vertices");
      in_facet = -1;
    } else if (key == "outer" || key == "endloop" || key == "endsolid") {
      // structure only
    } else {
      throw fail("unexpected '" + std::string(key) + "' in ASCII STL");
    }
  }
  if (!solid) throw InputError(source, "not an STL file (no 'solid' line)");
  if (in_facet >= 0) throw InputError(source, "the file ends inside a facet");
  TriMesh mesh;
  mesh.vertices = welder.vertices();
  mesh.faces = Eigen::Map<const Triangles>(corners.data(), static_cast<int>(corners.size() / 3), 3);
  return mesh;
}

}  // namespace

TriMesh read_stl(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string data = text::read_file(path);
  if (data.size() >= 84) {
    const auto count = load_le<std::uint32_t>(data.data() + 80);
    if (data.size() == 84 + 50 * static_cast<std::size_t>(count))
      return read_binary_stl(data, count);
  }
  const std::string_view head = text::trim(std::string_view(data).substr(0, 80));
  if (head.substr(0, 5) == "solid") return read_ascii_stl(source, data);
  if (data.size() >= 84)
    throw InputError(source, "binary STL size " + std::to_string(data.size()) +
                                 " bytes does not match its triangle count " +
                                 std::to_string(load_le<std::uint32_t>(data.data() + 80)));
  throw InputError(source, "not an STL file (too short for binary, no 'solid' for ASCII)");
}

void write_stl(const std::filesystem::path& path, const TriMesh& mesh) {
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        require_finite_matrix(mesh.vertices, "the vertex positions");
        std::string header = "binary STL written by tightfit";
        header.resize(80, ' ');
        out.write(header.data(), 80);
        put_le<std::uint32_t>(out, static_cast<std::uint32_t>(mesh.num_faces()));
        for (int f = 0; f < mesh.num_faces(); ++f) {
          const Vec3 a = mesh.vertices.row(mesh.faces(f, 0));
          const Vec3 b = mesh.vertices.row(mesh.faces(f, 1));
          const Vec3 c = mesh.vertices.row(mesh.faces(f, 2));
          Vec3 n = (b - a).cross(c - a);
          if (n.norm() > 0) n.normalize();
          for (int d = 0; d < 3; ++d) put_le<float>(out, static_cast<float>(n[d]));
          for (const Vec3* p : {&a, &b, &c})
            for (int d = 0; d < 3; ++d) put_le<float>(out, static_cast<float>((*p)[d]));
          put_le<std::uint16_t>(out, 0);
        }
      },
      true);
}

}  // namespace tightfit
