/// VTK XML UnstructuredGrid (.vtu, ascii) reader and writer (see tet_mesh_io.hpp).
#include <algorithm>
#include <map>
#include <ostream>
#include <stdexcept>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/xml_text.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

constexpr int kVtkTetra = 10;

void check_vtu_fields(const std::vector<MeshField>& fields, int rows, const char* what) {
  for (const auto& f : fields)
    if (f.name.empty() || f.values.rows() != rows || f.values.cols() < 1)
      throw std::invalid_argument(std::string("write_vtu: ") + what + " field '" + f.name +
                                  "' needs a name and " + std::to_string(rows) + " rows");
}

void write_data_arrays(std::ostream& out, const std::vector<MeshField>& fields) {
  for (const auto& f : fields) {
    out << "        <DataArray type=\"Float64\" Name=\"" << xml_escape(f.name)
        << "\" NumberOfComponents=\"" << f.values.cols() << "\" format=\"ascii\">\n";
    for (int r = 0; r < f.values.rows(); ++r) {
      out << "         ";
      for (int c = 0; c < f.values.cols(); ++c) out << ' ' << text::format_double(f.values(r, c));
      out << '\n';
    }
    out << "        </DataArray>\n";
  }
}

// ---- a minimal XML scanner: enough for VTK files --------------------------------

struct Tag {
  std::string name;
  std::map<std::string, std::string> attributes;
  bool closing = false;       // </name>
  bool self_closing = false;  // <name ... />
  std::size_t begin = 0;      // offset of '<'
  std::size_t end = 0;        // offset after '>'
};

class XmlScanner {
 public:
  XmlScanner(const std::string& source, const std::string& data) : source_(source), data_(data) {}

  /// The next element tag (skipping declarations, comments and text), or nullopt.
  std::optional<Tag> next() {
    while (true) {
      const std::size_t lt = data_.find('<', pos_);
      if (lt == std::string::npos) return std::nullopt;
      if (data_.compare(lt, 4, "<!--") == 0) {
        pos_ = skip_past(lt, "-->");
        continue;
      }
      if (data_.compare(lt, 2, "<?") == 0 || data_.compare(lt, 2, "<!") == 0) {
        pos_ = skip_past(lt, ">");
        continue;
      }
      const std::size_t gt = data_.find('>', lt);
      if (gt == std::string::npos) fail(lt, "unterminated tag");
      pos_ = gt + 1;
      return parse_tag(lt, gt);
    }
  }

  std::string_view text_between(std::size_t a, std::size_t b) const {
    return std::string_view(data_).substr(a, b - a);
  }

  [[noreturn]] void fail(std::size_t offset, const std::string& what) const {
    const auto line =
        1 + std::count(data_.begin(), data_.begin() + static_cast<long>(offset), '\n');
    throw InputError(source_, text::at_line(static_cast<int>(line)) + what);
  }

 private:
  std::size_t skip_past(std::size_t from, const char* terminator) const {
    const std::size_t p = data_.find(terminator, from);
    if (p == std::string::npos) fail(from, "unterminated XML markup");
    return p + std::char_traits<char>::length(terminator);
  }

  Tag parse_tag(std::size_t lt, std::size_t gt) const {
    Tag tag;
    tag.begin = lt;
    tag.end = gt + 1;
    std::string_view body = std::string_view(data_).substr(lt + 1, gt - lt - 1);
    if (!body.empty() && body.front() == '/') {
      tag.closing = true;
      body.remove_prefix(1);
    }
    if (!body.empty() && body.back() == '/') {
      tag.self_closing = true;
      body.remove_suffix(1);
    }
    std::size_t i = 0;
    auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (i < body.size() && !blank(body[i])) ++i;
    tag.name = std::string(body.substr(0, i));
    while (true) {
      while (i < body.size() && blank(body[i])) ++i;
      if (i >= body.size()) break;
      const std::size_t eq = body.find('=', i);
      if (eq == std::string_view::npos) fail(lt, "malformed attribute in <" + tag.name + ">");
      const std::string key(text::trim(body.substr(i, eq - i)));
      std::size_t q = eq + 1;
      while (q < body.size() && blank(body[q])) ++q;
      if (q >= body.size() || (body[q] != '"' && body[q] != '\''))
        fail(lt, "attribute '" + key + "' of <" + tag.name + "> is not quoted");
      const std::size_t close = body.find(body[q], q + 1);
      if (close == std::string_view::npos)
        fail(lt, "unterminated attribute '" + key + "' of <" + tag.name + ">");
      tag.attributes[key] = xml_unescape(body.substr(q + 1, close - q - 1));
      i = close + 1;
    }
    return tag;
  }

  const std::string& source_;
  const std::string& data_;
  std::size_t pos_ = 0;
};

struct DataArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
  std::size_t offset = 0;  // for error messages
};

std::string attribute(const Tag& tag, const std::string& key, const std::string& fallback = "") {
  const auto it = tag.attributes.find(key);
  return it == tag.attributes.end() ? fallback : it->second;
}

/// Reads the <DataArray> whose opening tag is `open` up to its closing tag.
DataArray read_data_array(XmlScanner& xml, const Tag& open) {
  DataArray array;
  array.name = attribute(open, "Name");
  array.offset = open.begin;
  const std::string format = attribute(open, "format", "ascii");
  if (format != "ascii")
    xml.fail(open.begin, "DataArray '" + array.name + "' has format '" + format +
                             "'; only ascii .vtu files are supported");
  const auto components = text::to_int(attribute(open, "NumberOfComponents", "1"));
  if (!components || *components < 1)
    xml.fail(open.begin, "DataArray '" + array.name + "' has a bad NumberOfComponents");
  array.components = static_cast<int>(*components);
  if (open.self_closing) return array;
  const auto close = xml.next();
  if (!close || !close->closing || close->name != "DataArray")
    xml.fail(open.begin, "DataArray '" + array.name + "' is not closed");
  std::vector<std::string_view> tokens;
  text::split(xml.text_between(open.end, close->begin), tokens);
  array.values.reserve(tokens.size());
  for (const auto& tok : tokens) {
    const auto value = text::to_double(tok);
    if (!value)
      xml.fail(open.begin, "DataArray '" + array.name + "' has a value '" + std::string(tok) +
                               "' that is not a number");
    array.values.push_back(*value);
  }
  return array;
}

MeshField to_field(XmlScanner& xml, const DataArray& array, std::int64_t rows, const char* what) {
  if (static_cast<std::int64_t>(array.values.size()) != rows * array.components)
    xml.fail(array.offset, std::string(what) + " array '" + array.name + "' has " +
                               std::to_string(array.values.size()) + " values, expected " +
                               std::to_string(rows * array.components));
  MeshField field{array.name, MatX(rows, array.components)};
  for (std::int64_t r = 0; r < rows; ++r)
    for (int c = 0; c < array.components; ++c)
      field.values(r, c) = array.values[r * array.components + c];
  return field;
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const TetMesh& mesh,
               const std::vector<MeshField>& point_fields,
               const std::vector<MeshField>& cell_fields) {
  check_vtu_fields(point_fields, mesh.num_vertices(), "point");
  check_vtu_fields(cell_fields, mesh.num_tets(), "cell");
  write_file_atomically(path, [&](std::ostream& out) {
    require_finite_matrix(mesh.vertices, "the point positions");
    for (const auto& f : point_fields)
      require_finite_matrix(f.values, "the point field '" + f.name + "'");
    for (const auto& f : cell_fields)
      require_finite_matrix(f.values, "the cell field '" + f.name + "'");
    out << "<?xml version=\"1.0\"?>\n"
        << "<!-- written by tightfit -->\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << mesh.num_vertices() << "\" NumberOfCells=\""
        << mesh.num_tets() << "\">\n";
    out << "      <PointData>\n";
    write_data_arrays(out, point_fields);
    out << "      </PointData>\n      <CellData>\n";
    write_data_arrays(out, cell_fields);
    out << "      </CellData>\n      <Points>\n"
        << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    for (int i = 0; i < mesh.num_vertices(); ++i)
      out << "          " << text::format_double(mesh.vertices(i, 0)) << ' '
          << text::format_double(mesh.vertices(i, 1)) << ' '
          << text::format_double(mesh.vertices(i, 2)) << '\n';
    out << "        </DataArray>\n      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (int t = 0; t < mesh.num_tets(); ++t)
      out << "          " << mesh.tets(t, 0) << ' ' << mesh.tets(t, 1) << ' ' << mesh.tets(t, 2)
          << ' ' << mesh.tets(t, 3) << '\n';
    out << "        </DataArray>\n"
        << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (int t = 0; t < mesh.num_tets(); ++t) out << "          " << 4 * (t + 1) << '\n';
    out << "        </DataArray>\n"
        << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (int t = 0; t < mesh.num_tets(); ++t) out << "          " << kVtkTetra << '\n';
    out << "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
        << "</VTKFile>\n";
  });
}

VtuData read_vtu(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string data = text::read_file(path);
  XmlScanner xml(source, data);

  bool is_vtk = false;
  int pieces = 0;
  std::int64_t num_points = -1, num_cells = -1;
  std::size_t piece_offset = 0;
  std::string section;  // PointData, CellData, Points, Cells or empty
  std::vector<DataArray> point_arrays, cell_arrays;
  std::optional<DataArray> points, connectivity, offsets, types;

  while (auto tag = xml.next()) {
    if (tag->closing) {
      if (tag->name == section) section.clear();
      continue;
    }
    if (tag->name == "VTKFile") {
      if (attribute(*tag, "type") != "UnstructuredGrid")
        xml.fail(tag->begin,
                 "VTKFile type '" + attribute(*tag, "type") + "' is not UnstructuredGrid");
      is_vtk = true;
    } else if (tag->name == "Piece") {
      if (++pieces > 1) xml.fail(tag->begin, "more than one Piece is not supported");
      const auto np = text::to_int(attribute(*tag, "NumberOfPoints"));
      const auto nc = text::to_int(attribute(*tag, "NumberOfCells"));
      if (!np || !nc || *np < 0 || *nc < 0 || *np > (1 << 30) || *nc > (1 << 30))
        xml.fail(tag->begin, "Piece needs NumberOfPoints and NumberOfCells");
      num_points = *np;
      num_cells = *nc;
      piece_offset = tag->begin;
    } else if (tag->name == "PointData" || tag->name == "CellData" || tag->name == "Points" ||
               tag->name == "Cells") {
      if (!tag->self_closing) section = tag->name;
    } else if (tag->name == "DataArray") {
      DataArray array = read_data_array(xml, *tag);
      if (section == "PointData")
        point_arrays.push_back(std::move(array));
      else if (section == "CellData")
        cell_arrays.push_back(std::move(array));
      else if (section == "Points")
        points = std::move(array);
      else if (section == "Cells") {
        if (array.name == "connectivity")
          connectivity = std::move(array);
        else if (array.name == "offsets")
          offsets = std::move(array);
        else if (array.name == "types")
          types = std::move(array);
      }
    } else if (tag->name == "AppendedData") {
      xml.fail(tag->begin, "appended data is not supported; only ascii .vtu files are");
    }
  }
  if (!is_vtk) throw InputError(source, "not a VTK XML file (no <VTKFile> element)");
  if (pieces == 0) throw InputError(source, "no <Piece> element");
  if (!points) xml.fail(piece_offset, "the piece has no <Points> data array");
  if (!connectivity || !offsets || !types)
    xml.fail(piece_offset, "<Cells> needs connectivity, offsets and types arrays");

  VtuData out;
  const MeshField p = to_field(xml, *points, num_points, "Points");
  if (p.values.cols() != 3) xml.fail(points->offset, "Points must have 3 components");
  out.mesh.vertices = p.values;
  if (static_cast<std::int64_t>(types->values.size()) != num_cells ||
      static_cast<std::int64_t>(offsets->values.size()) != num_cells)
    xml.fail(types->offset,
             "types and offsets need one value per cell (" + std::to_string(num_cells) + ")");
  out.mesh.tets.resize(num_cells, 4);
  std::int64_t previous = 0;
  for (std::int64_t c = 0; c < num_cells; ++c) {
    if (types->values[c] != kVtkTetra)
      xml.fail(types->offset, "cell " + std::to_string(c) + " has VTK type " +
                                  text::format_double(types->values[c]) +
                                  "; only tetrahedra (type 10) are supported");
    const auto end = static_cast<std::int64_t>(offsets->values[c]);
    if (end != previous + 4 || end > static_cast<std::int64_t>(connectivity->values.size()))
      xml.fail(offsets->offset, "offset of cell " + std::to_string(c) + " is inconsistent");
    for (int k = 0; k < 4; ++k) {
      const double v = connectivity->values[previous + k];
      if (v < 0 || v >= static_cast<double>(num_points) ||
          v != static_cast<double>(static_cast<std::int64_t>(v)))
        xml.fail(connectivity->offset, "cell " + std::to_string(c) + " refers to point " +
                                           text::format_double(v) + ", the piece has " +
                                           std::to_string(num_points) + " points");
      out.mesh.tets(c, k) = static_cast<int>(v);
    }
    previous = end;
  }
  for (const auto& a : point_arrays)
    out.point_fields.push_back(to_field(xml, a, num_points, "PointData"));
  for (const auto& a : cell_arrays)
    out.cell_fields.push_back(to_field(xml, a, num_cells, "CellData"));
  return out;
}

}  // namespace tightfit
