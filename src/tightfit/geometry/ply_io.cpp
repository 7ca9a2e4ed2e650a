/// PLY reader and writer (see mesh_io.hpp).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

// The enumerators are PLY's own keywords.
// NOLINTBEGIN(readability-identifier-naming)
enum class Format { ascii, binary_le, binary_be };
enum class Type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };
// NOLINTEND(readability-identifier-naming)

std::optional<Type> parse_type(std::string_view name) {
  if (name == "char" || name == "int8") return Type::int8;
  if (name == "uchar" || name == "uint8") return Type::uint8;
  if (name == "short" || name == "int16") return Type::int16;
  if (name == "ushort" || name == "uint16") return Type::uint16;
  if (name == "int" || name == "int32") return Type::int32;
  if (name == "uint" || name == "uint32") return Type::uint32;
  if (name == "float" || name == "float32") return Type::float32;
  if (name == "double" || name == "float64") return Type::float64;
  return std::nullopt;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::int8:
    case Type::uint8:
      return 1;
    case Type::int16:
    case Type::uint16:
      return 2;
    case Type::int32:
    case Type::uint32:
    case Type::float32:
      return 4;
    case Type::float64:
      return 8;
  }
  return 0;
}

bool is_integer(Type t) { return t != Type::float32 && t != Type::float64; }

struct Property {
  std::string name;
  Type type = Type::float64;
  bool is_list = false;
  Type count_type = Type::uint8;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
  int header_line = 0;
};

/// Sequential reader of the body, ascii or binary, with error messages naming the
/// element and the position.
class BodyReader {
 public:
  BodyReader(const std::string& source, const std::string& data, std::size_t start, Format format,
             int first_line)
      : source_(source),
        data_(data),
        pos_(start),
        format_(format),
        cursor_(data, start),
        line_base_(first_line) {}

  /// Starts element instance `index` of `element` (ascii: reads its line).
  void begin_instance(const Element& element, std::int64_t index) {
    element_ = &element;
    index_ = index;
    if (format_ != Format::ascii) return;
    while (true) {
      const auto line = cursor_.next();
      if (!line) fail("the file ends before the data of " + where());
      text::split(text::strip_comment(*line), tokens_);
      if (!tokens_.empty()) break;
    }
    token_ = 0;
  }

  double read(Type type) {
    if (format_ == Format::ascii) {
      if (token_ >= tokens_.size()) fail("too few values for " + where());
      const std::string_view tok = tokens_[token_++];
      const auto value = text::to_double(tok);
      if (!value) fail("value '" + std::string(tok) + "' of " + where() + " is not a number");
      return *value;
    }
    const std::size_t size = type_size(type);
    if (pos_ + size > data_.size()) fail("the file ends inside the data of " + where());
    unsigned char bytes[8];
    std::memcpy(bytes, data_.data() + pos_, size);
    pos_ += size;
    const bool file_little = format_ == Format::binary_le;
    if (file_little != (std::endian::native == std::endian::little))
      std::reverse(bytes, bytes + size);
    switch (type) {
      case Type::int8:
        return static_cast<double>(static_cast<std::int8_t>(bytes[0]));
      case Type::uint8:
        return static_cast<double>(bytes[0]);
      case Type::int16:
        return load<std::int16_t>(bytes);
      case Type::uint16:
        return load<std::uint16_t>(bytes);
      case Type::int32:
        return load<std::int32_t>(bytes);
      case Type::uint32:
        return load<std::uint32_t>(bytes);
      case Type::float32:
        return load<float>(bytes);
      case Type::float64:
        return load<double>(bytes);
    }
    return 0.0;
  }

  /// Ascii: checks that the instance line has no extra values.
  void end_instance() {
    if (format_ == Format::ascii && token_ != tokens_.size())
      fail("too many values for " + where());
  }

  [[noreturn]] void fail(const std::string& what) const {
    if (format_ == Format::ascii)
      throw InputError(source_, text::at_line(line_base_ + cursor_.line_number()) + what);
    throw InputError(source_, "binary data at byte " + std::to_string(pos_) + ": " + what);
  }

  std::string where() const {
    return element_ ? element_->name + " " + std::to_string(index_) : std::string("the body");
  }

 private:
  template <class T>
  static double load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  const std::string& source_;
  const std::string& data_;
  std::size_t pos_;
  Format format_;
  text::LineCursor cursor_;
  int line_base_;
  std::vector<std::string_view> tokens_;
  std::size_t token_ = 0;
  const Element* element_ = nullptr;
  std::int64_t index_ = 0;
};

bool is_index_list_name(const std::string& name) {
  return name == "vertex_indices" || name == "vertex_index";
}

}  // namespace

PlyData read_ply(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string data = text::read_file(path);
  text::LineCursor cursor(data);
  std::vector<std::string_view> tokens;

  const auto first = cursor.next();
  if (!first || text::trim(*first) != "ply")
    throw InputError(source, "not a PLY file (the first line must be 'ply')");

  std::optional<Format> format;
  std::vector<Element> elements;
  bool ended = false;
  while (auto line = cursor.next()) {
    const int ln = cursor.line_number();
    text::split(*line, tokens);
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (tokens.size() < 2) throw InputError(source, text::at_line(ln) + "format without a name");
      if (tokens[1] == "ascii")
        format = Format::ascii;
      else if (tokens[1] == "binary_little_endian")
        format = Format::binary_le;
      else if (tokens[1] == "binary_big_endian")
        format = Format::binary_be;
      else
        throw InputError(source,
                         text::at_line(ln) + "unknown PLY format '" + std::string(tokens[1]) + "'");
    } else if (key == "element") {
      const auto count = tokens.size() == 3 ? text::to_int(tokens[2]) : std::nullopt;
      if (!count || *count < 0)
        throw InputError(source, text::at_line(ln) + "expected 'element NAME COUNT'");
      elements.push_back({std::string(tokens[1]), *count, {}, ln});
    } else if (key == "property") {
      if (elements.empty())
        throw InputError(source, text::at_line(ln) + "property before any element");
      Property prop;
      if (tokens.size() == 5 && tokens[1] == "list") {
        const auto ct = parse_type(tokens[2]);
        const auto it = parse_type(tokens[3]);
        if (!ct || !it || !is_integer(*ct))
          throw InputError(source, text::at_line(ln) + "bad list property types '" +
                                       std::string(tokens[2]) + " " + std::string(tokens[3]) + "'");
        prop = {std::string(tokens[4]), *it, true, *ct};
      } else if (tokens.size() == 3) {
        const auto t = parse_type(tokens[1]);
        if (!t)
          throw InputError(
              source, text::at_line(ln) + "unknown property type '" + std::string(tokens[1]) + "'");
        prop = {std::string(tokens[2]), *t, false, Type::uint8};
      } else {
        throw InputError(source, text::at_line(ln) + "malformed property line");
      }
      elements.back().properties.push_back(prop);
    } else {
      throw InputError(source,
                       text::at_line(ln) + "unknown header keyword '" + std::string(key) + "'");
    }
  }
  if (!ended) throw InputError(source, "the header has no 'end_header' line");
  if (!format) throw InputError(source, "the header has no 'format' line");

  const Element* vertex_el = nullptr;
  const Element* face_el = nullptr;
  for (const auto& el : elements) {
    if (el.name == "vertex") vertex_el = &el;
    if (el.name == "face") face_el = &el;
  }
  if (!vertex_el) throw InputError(source, "no 'vertex' element in the header");
  int xyz[3] = {-1, -1, -1};
  for (int k = 0; k < static_cast<int>(vertex_el->properties.size()); ++k) {
    const auto& p = vertex_el->properties[k];
    if (p.is_list) continue;
    if (p.name == "x") xyz[0] = k;
    if (p.name == "y") xyz[1] = k;
    if (p.name == "z") xyz[2] = k;
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
    throw InputError(source, text::at_line(vertex_el->header_line) +
                                 "the vertex element lacks an x, y or z property");
  int index_list = -1;
  if (face_el) {
    for (int k = 0; k < static_cast<int>(face_el->properties.size()); ++k)
      if (face_el->properties[k].is_list && is_index_list_name(face_el->properties[k].name))
        index_list = k;
    if (index_list < 0)
      throw InputError(source, text::at_line(face_el->header_line) +
                                   "the face element has no vertex_indices list");
  }
  // Reject element counts the file cannot hold before allocating for them: an ascii
  // instance takes at least two bytes, a binary one the sizes of its scalars and
  // list counts (at least one byte).
  {
    const double available = static_cast<double>(data.size() - cursor.position());
    double needed = 0.0;
    for (const auto& el : elements) {
      std::size_t bytes = 0;
      for (const auto& p : el.properties) bytes += type_size(p.is_list ? p.count_type : p.type);
      // An instance without properties is charged one byte: a header may not ask for
      // billions of empty instances.
      needed += static_cast<double>(el.count) *
                static_cast<double>(*format == Format::ascii ? 2 : std::max<std::size_t>(bytes, 1));
    }
    if (needed > available || vertex_el->count > std::numeric_limits<int>::max() ||
        (face_el && face_el->count > std::numeric_limits<int>::max()))
      throw InputError(source,
                       "the element counts in the header are larger than the file can hold");
  }

  // Column layout of the attributes: every scalar property except x, y, z (and
  // red/green/blue when all three exist) becomes a field.
  auto find = [](const Element& el, const char* name) {
    for (int k = 0; k < static_cast<int>(el.properties.size()); ++k)
      if (!el.properties[k].is_list && el.properties[k].name == name) return k;
    return -1;
  };
  const int rgb[3] = {find(*vertex_el, "red"), find(*vertex_el, "green"), find(*vertex_el, "blue")};
  const bool has_colors = rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0;
  std::vector<int> vertex_field_of(vertex_el->properties.size(), -1);
  PlyData out;
  for (int k = 0; k < static_cast<int>(vertex_el->properties.size()); ++k) {
    const auto& p = vertex_el->properties[k];
    const bool is_color = has_colors && (k == rgb[0] || k == rgb[1] || k == rgb[2]);
    if (p.is_list || k == xyz[0] || k == xyz[1] || k == xyz[2] || is_color) continue;
    vertex_field_of[k] = static_cast<int>(out.attributes.vertex_fields.size());
    out.attributes.vertex_fields.push_back({p.name, MatX(vertex_el->count, 1)});
  }
  std::vector<int> face_field_of(face_el ? face_el->properties.size() : 0, -1);
  std::vector<std::vector<double>> face_field_values;
  if (face_el)
    for (int k = 0; k < static_cast<int>(face_el->properties.size()); ++k) {
      if (face_el->properties[k].is_list) continue;
      face_field_of[k] = static_cast<int>(face_field_values.size());
      face_field_values.emplace_back();
      out.attributes.face_fields.push_back({face_el->properties[k].name, MatX()});
    }

  const int nv = static_cast<int>(vertex_el->count);
  out.mesh.vertices.resize(nv, 3);
  if (has_colors) out.attributes.vertex_colors.resize(nv, 3);
  std::vector<int> corners;
  std::vector<double> polygon_values;
  std::vector<int> polygon;

  BodyReader body(source, data, cursor.position(), *format, cursor.line_number());
  for (const auto& el : elements) {
    for (std::int64_t i = 0; i < el.count; ++i) {
      body.begin_instance(el, i);
      polygon_values.assign(el.properties.size(), 0.0);
      polygon.clear();
      for (int k = 0; k < static_cast<int>(el.properties.size()); ++k) {
        const auto& p = el.properties[k];
        if (!p.is_list) {
          polygon_values[k] = body.read(p.type);
          continue;
        }
        const double count = body.read(p.count_type);
        if (count < 0 || count != std::floor(count))
          body.fail("bad list length " + text::format_double(count) + " in " + body.where());
        if (count > static_cast<double>(data.size()))  // every entry takes at least one byte
          body.fail("list length " + text::format_double(count) + " in " + body.where() +
                    " is longer than the file");
        const bool keep = (&el == face_el && k == index_list);
        for (int c = 0; c < static_cast<int>(count); ++c) {
          const double value = body.read(p.type);
          if (!keep) continue;
          if (value != std::floor(value) || value < 0 || value >= nv)
            body.fail(body.where() + " refers to vertex " + text::format_double(value) +
                      ", the file has " + std::to_string(nv) + " vertices");
          polygon.push_back(static_cast<int>(value));
        }
      }
      body.end_instance();
      if (&el == vertex_el) {
        for (int d = 0; d < 3; ++d) out.mesh.vertices(i, d) = polygon_values[xyz[d]];
        if (has_colors)
          for (int d = 0; d < 3; ++d)  // clamped into 0..255 like any colour; NaN gives 0
            out.attributes.vertex_colors(i, d) = static_cast<std::uint8_t>(
                std::fmin(std::fmax(std::round(polygon_values[rgb[d]]), 0.0), 255.0));
        for (int k = 0; k < static_cast<int>(el.properties.size()); ++k)
          if (vertex_field_of[k] >= 0)
            out.attributes.vertex_fields[vertex_field_of[k]].values(i, 0) = polygon_values[k];
      } else if (&el == face_el) {
        if (polygon.size() < 3)
          body.fail(body.where() + " has " + std::to_string(polygon.size()) +
                    " vertices, at least 3 are needed");
        for (std::size_t c = 1; c + 1 < polygon.size(); ++c) {
          corners.insert(corners.end(), {polygon[0], polygon[c], polygon[c + 1]});
          for (int k = 0; k < static_cast<int>(el.properties.size()); ++k)
            if (face_field_of[k] >= 0)
              face_field_values[face_field_of[k]].push_back(polygon_values[k]);
        }
      }
    }
  }
  const int nf = static_cast<int>(corners.size() / 3);
  out.mesh.faces = Eigen::Map<const Triangles>(corners.data(), nf, 3);
  for (std::size_t k = 0; k < face_field_values.size(); ++k)
    out.attributes.face_fields[k].values = Eigen::Map<const VecX>(face_field_values[k].data(), nf);
  return out;
}

namespace {

void check_ply_fields(const std::vector<MeshField>& fields, int rows, const char* what) {
  for (const auto& f : fields) {
    if (f.name.empty() || f.name.find_first_of(" \t\r\n") != std::string::npos)
      throw std::invalid_argument(std::string("write_ply: bad ") + what + " field name '" + f.name +
                                  "'");
    if (f.values.rows() != rows || f.values.cols() < 1)
      throw std::invalid_argument(std::string("write_ply: ") + what + " field '" + f.name +
                                  "' has " + std::to_string(f.values.rows()) + " rows, expected " +
                                  std::to_string(rows));
  }
}

void write_property_names(std::ostream& out, const std::vector<MeshField>& fields) {
  for (const auto& f : fields) {
    if (f.values.cols() == 1) {
      out << "property double " << f.name << '\n';
    } else {
      for (int c = 0; c < f.values.cols(); ++c)
        out << "property double " << f.name << '_' << c << '\n';
    }
  }
}

template <class T>
void put(std::ostream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.write(bytes, sizeof(T));
}

void put_value(std::ostream& out, double value, bool binary, bool& first) {
  if (binary) {
    put(out, value);
  } else {
    if (!first) out << ' ';
    out << text::format_double(value);
  }
  first = false;
}

}  // namespace

void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               const PlyAttributes& attributes, PlyEncoding encoding) {
  const int nv = mesh.num_vertices();
  const int nf = mesh.num_faces();
  check_ply_fields(attributes.vertex_fields, nv, "vertex");
  check_ply_fields(attributes.face_fields, nf, "face");
  const bool colors = attributes.vertex_colors.rows() > 0;
  if (colors && attributes.vertex_colors.rows() != nv)
    throw std::invalid_argument("write_ply: vertex_colors needs one row per vertex");
  const bool binary = encoding == PlyEncoding::binary_little_endian;
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        require_finite_matrix(mesh.vertices, "the vertex positions");
        for (const auto& f : attributes.vertex_fields)
          require_finite_matrix(f.values, "the vertex field '" + f.name + "'");
        for (const auto& f : attributes.face_fields)
          require_finite_matrix(f.values, "the face field '" + f.name + "'");
        out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
            << "comment written by tightfit\n"
            << "element vertex " << nv << '\n'
            << "property double x\nproperty double y\nproperty double z\n";
        write_property_names(out, attributes.vertex_fields);
        if (colors) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
        out << "element face " << nf << '\n' << "property list uchar int vertex_indices\n";
        write_property_names(out, attributes.face_fields);
        out << "end_header\n";
        for (int i = 0; i < nv; ++i) {
          bool first = true;
          for (int d = 0; d < 3; ++d) put_value(out, mesh.vertices(i, d), binary, first);
          for (const auto& f : attributes.vertex_fields)
            for (int c = 0; c < f.values.cols(); ++c) put_value(out, f.values(i, c), binary, first);
          if (colors) {
            for (int d = 0; d < 3; ++d) {
              const std::uint8_t value = attributes.vertex_colors(i, d);
              if (binary)
                out.put(static_cast<char>(value));
              else
                out << ' ' << static_cast<int>(value);
            }
          }
          if (!binary) out << '\n';
        }
        for (int f = 0; f < nf; ++f) {
          if (binary) {
            out.put(3);
            for (int d = 0; d < 3; ++d) put<std::int32_t>(out, mesh.faces(f, d));
          } else {
            out << "3 " << mesh.faces(f, 0) << ' ' << mesh.faces(f, 1) << ' ' << mesh.faces(f, 2);
          }
          bool first = false;
          for (const auto& field : attributes.face_fields)
            for (int c = 0; c < field.values.cols(); ++c)
              put_value(out, field.values(f, c), binary, first);
          if (!binary) out << '\n';
        }
      },
      binary);
}

void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               const std::vector<MeshField>& face_fields, const VertexColors& vertex_colors,
               PlyEncoding encoding) {
  PlyAttributes attributes;
  attributes.face_fields = face_fields;
  attributes.vertex_colors = vertex_colors;
  write_ply(path, mesh, attributes, encoding);
}

}  // namespace tightfit
