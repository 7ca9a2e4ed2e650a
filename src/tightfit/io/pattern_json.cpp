#include "tightfit/io/pattern_json.hpp"

#include <nlohmann/json.hpp>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/io/pattern_drawing.hpp"
#include "tightfit/io/pattern_validate.hpp"
#include "tightfit/io/seam_statistics.hpp"

#include <stdexcept>

namespace tightfit {
namespace {

using nlohmann::json;

json point(const Vec2& q) { return json::array({q.x(), q.y()}); }

json polygon(const Polygon2& polygon) {
  json out = json::array();
  for (const Vec2& q : polygon) out.push_back(point(q));
  return out;
}

json openings_mm(const PieceDrawing& drawing) {
  json out = json::array();
  for (const Polygon2& hole : drawing.holes) out.push_back(polygon(hole));
  return out;
}

json side_json(const Pattern& pattern, int piece, const std::vector<int>& vertices) {
  return {{"piece", piece},
          {"piece_name", pattern.pieces[static_cast<size_t>(piece)].name},
          {"vertices", vertices}};
}

json piece_json(const PatternPiece& piece, const PieceDrawing& drawing) {
  json rest = json::array();
  for (Eigen::Index i = 0; i < piece.rest.rows(); ++i) {
    rest.push_back(json::array({piece.rest(i, 0), piece.rest(i, 1)}));
  }
  json triangles = json::array();
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    triangles.push_back(
        json::array({piece.triangles(t, 0), piece.triangles(t, 1), piece.triangles(t, 2)}));
  }
  json notches = json::array();
  for (const Notch& n : drawing.notches) {
    notches.push_back({{"seam", n.seam},
                       {"side", n.side == 0 ? "a" : "b"},
                       {"index", n.index},
                       {"sew", point(n.sew)},
                       {"cut", point(n.cut)},
                       {"style", n.style == NotchStyle::kDouble ? "double" : "single"}});
  }
  return {{"name", piece.name},
          {"quantity", drawing.quantity},
          {"rest", rest},
          {"triangles", triangles},
          {"boundary", piece.boundary},
          {"holes", piece.holes},
          {"corners", piece.corners},
          {"grain", point(piece.grain)},
          {"sew_line_mm", polygon(drawing.sew_line)},
          {"cut_line_mm", polygon(drawing.cut_line)},
          {"openings_mm", openings_mm(drawing)},
          {"allowance_mm", drawing.allowance},
          {"grain_line_mm", json::array({point(drawing.grain_start), point(drawing.grain_end)})},
          {"notches_mm", notches}};
}

/// An array of arrays of `width` numbers (JSON path `key` of `fields`).
template <typename Scalar>
std::vector<std::vector<Scalar>> read_rows(JsonFields& fields, const std::string& key, int width) {
  const json& j = fields.raw(key);
  if (j.is_null()) fields.fail("missing (expected an array)", key);
  if (!j.is_array()) fields.fail(std::string("expected an array, got ") + j.type_name(), key);
  std::vector<std::vector<Scalar>> rows;
  for (size_t i = 0; i < j.size(); ++i) {
    const json& row = j[i];
    const std::string where = key + "/" + std::to_string(i);
    if (!row.is_array() || static_cast<int>(row.size()) != width) {
      fields.fail("expected an array of " + std::to_string(width) + " numbers", where);
    }
    std::vector<Scalar> values;
    for (const json& v : row) {
      const bool ok = std::is_integral_v<Scalar> ? v.is_number_integer() : v.is_number();
      if (!ok) {
        fields.fail(std::is_integral_v<Scalar> ? "expected integers" : "expected numbers", where);
      }
      values.push_back(v.get<Scalar>());
    }
    rows.push_back(std::move(values));
  }
  return rows;
}

std::vector<int> read_indices(JsonFields& fields, const std::string& key) {
  const json& j = fields.raw(key);
  if (j.is_null()) fields.fail("missing (expected an array of integers)", key);
  if (!j.is_array()) fields.fail("expected an array of integers", key);
  std::vector<int> out;
  for (const json& v : j) {
    if (!v.is_number_integer()) fields.fail("expected an array of integers", key);
    out.push_back(v.get<int>());
  }
  return out;
}

PatternPiece read_piece(JsonFields& f) {
  PatternPiece piece;
  piece.name = f.string("name");
  f.raw("quantity");
  const auto rest = read_rows<double>(f, "rest", 2);
  piece.rest.resize(static_cast<Eigen::Index>(rest.size()), 2);
  for (size_t i = 0; i < rest.size(); ++i) {
    piece.rest(static_cast<Eigen::Index>(i), 0) = rest[i][0];
    piece.rest(static_cast<Eigen::Index>(i), 1) = rest[i][1];
  }
  const auto triangles = read_rows<int>(f, "triangles", 3);
  piece.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      piece.triangles(static_cast<Eigen::Index>(t), k) = triangles[t][static_cast<size_t>(k)];
    }
  }
  piece.boundary = read_indices(f, "boundary");
  const json& holes = f.raw("holes");
  if (!holes.is_null()) {
    if (!holes.is_array()) f.fail("expected an array of vertex loops", "holes");
    for (const json& loop : holes) {
      if (!loop.is_array())
        f.fail("expected an array of vertex loops (arrays of integers)", "holes");
      std::vector<int> vertices;
      for (const json& v : loop) {
        if (!v.is_number_integer())
          f.fail("expected an array of vertex loops (arrays of integers)", "holes");
        vertices.push_back(v.get<int>());
      }
      piece.holes.push_back(std::move(vertices));
    }
  }
  piece.corners = read_indices(f, "corners");
  piece.grain = f.vec2("grain");
  for (const char* derived : {"sew_line_mm", "cut_line_mm", "openings_mm", "allowance_mm",
                              "grain_line_mm", "notches_mm"}) {
    f.raw(derived);
  }
  f.finish();
  return piece;
}

void read_side(JsonFields& f, int& piece, std::vector<int>& vertices) {
  piece = f.integer("piece");
  f.string("piece_name", "");
  vertices = read_indices(f, "vertices");
  f.finish();
}

}  // namespace

void write_pieces_json(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path,
                       const std::vector<SeamStatistics>* fit_seams) {
  const std::vector<PieceDrawing> drawings = draw_pattern_pieces(pattern, options, path.string());
  json root = {{"format", "tightfit-pieces"},
               {"version", 1},
               {"units", {{"rest", "m"}, {"outlines", "mm"}}},
               {"seam_allowance_m", options.seam_allowance}};
  json pieces = json::array();
  for (size_t p = 0; p < pattern.pieces.size(); ++p) {
    pieces.push_back(piece_json(pattern.pieces[p], drawings[p]));
  }
  root["pieces"] = pieces;
  if (fit_seams && fit_seams->size() != pattern.seams.size())
    throw std::invalid_argument("write_pieces_json: one fit statistic per seam expected");
  const std::vector<SeamStatistics> lengths = pattern_seam_statistics(pattern);
  json seams = json::array();
  for (size_t k = 0; k < pattern.seams.size(); ++k) {
    const Seam& seam = pattern.seams[k];
    json entry = {{"name", seam.name},
                  {"a", side_json(pattern, seam.a.piece, seam.a.vertices)},
                  {"b", side_json(pattern, seam.b.piece, seam.b.vertices)},
                  {"length_a_mm", 1000.0 * lengths[k].length_a},
                  {"length_b_mm", 1000.0 * lengths[k].length_b},
                  {"mismatch_mm", 1000.0 * lengths[k].mismatch()}};
    if (fit_seams) {
      json fit = seam_statistics_json((*fit_seams)[k]);
      for (const char* key :
           {"name", "piece_a", "piece_b", "length_a_mm", "length_b_mm", "mismatch_mm"})
        fit.erase(key);
      entry["fit"] = fit;
    }
    seams.push_back(entry);
  }
  root["seams"] = seams;
  json pinned = json::array();
  for (const PinnedBoundary& pin : pattern.pinned) {
    json side = side_json(pattern, pin.piece, pin.vertices);
    side["name"] = pin.name;
    pinned.push_back(side);
  }
  root["pinned"] = pinned;
  write_json_atomically(path, root, 1);
}

Pattern read_pieces_json(const std::filesystem::path& path) {
  const std::string source = path.string();
  const json root = read_json_file(source);
  JsonFields f(root, source, "");
  if (f.string("format") != "tightfit-pieces") f.fail("expected \"tightfit-pieces\"", "format");
  if (f.integer("version") != 1) f.fail("unsupported version (expected 1)", "version");
  f.raw("units");
  f.raw("seam_allowance_m");
  Pattern pattern;
  for (JsonFields& piece : f.objects("pieces", true)) pattern.pieces.push_back(read_piece(piece));
  for (JsonFields& s : f.objects("seams")) {
    Seam seam;
    seam.name = s.string("name");
    auto a = s.object("a", true);
    read_side(*a, seam.a.piece, seam.a.vertices);
    auto b = s.object("b", true);
    read_side(*b, seam.b.piece, seam.b.vertices);
    for (const char* derived : {"length_a_mm", "length_b_mm", "mismatch_mm", "fit"}) s.raw(derived);
    s.finish();
    pattern.seams.push_back(std::move(seam));
  }
  for (JsonFields& p : f.objects("pinned")) {
    PinnedBoundary pin;
    pin.name = p.string("name");
    read_side(p, pin.piece, pin.vertices);
    pattern.pinned.push_back(std::move(pin));
  }
  f.finish();
  validate_pattern(pattern, source);
  return pattern;
}

}  // namespace tightfit
