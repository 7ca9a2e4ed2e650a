#include "tightfit/scene/pattern_record.hpp"

#include <cmath>
#include <set>

#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit {
namespace {

using nlohmann::json;

std::string element_path(const std::string& path, size_t i) {
  return path + "/" + std::to_string(i);
}

json record_rows_json(const auto& m) {
  json a = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(i, c));
    a.push_back(std::move(row));
  }
  return a;
}

/// Throws unless `v` is a vertex index in [0, n) (JSON path `path` in `source`).
void check_index(const json& v, int n, const std::string& source, const std::string& path) {
  if (!v.is_number_integer())
    throw InputError(source, path + ": expected a vertex index (an integer)");
  const long long i = v.get<long long>();
  if (i < 0 || i >= n) {
    std::string what = path;
    what += ": vertex index ";
    what += std::to_string(i);
    what += " is out of range [0, ";
    what += std::to_string(n);
    what += ")";
    throw InputError(source, what);
  }
}

/// Indices in [0, n) at member `key` of `f`.
std::vector<int> read_indices(JsonFields& f, const std::string& key, int n) {
  const json& j = f.raw(key);
  if (!j.is_array()) f.fail("expected an array of vertex indices", key);
  std::vector<int> out;
  for (size_t i = 0; i < j.size(); ++i) {
    check_index(j[i], n, f.source(), element_path(f.child_path(key), i));
    out.push_back(j[i].get<int>());
  }
  return out;
}

/// Marks the `keys` of `f` as known.
void accept(JsonFields& f, const std::vector<std::string>& keys) {
  for (const std::string& key : keys) f.raw(key);
}

PatternPiece read_piece(JsonFields& f, const std::vector<std::string>& extra) {
  PatternPiece piece;
  piece.name = f.string("name");
  if (piece.name.empty()) f.fail("expected a non-empty name", "name");
  const json& rest = f.raw("rest");
  const std::string rest_path = f.child_path("rest");
  if (!rest.is_array() || rest.size() < 3)
    f.fail("expected an array of at least 3 [x, y] positions", "rest");
  piece.rest.resize(static_cast<Eigen::Index>(rest.size()), 2);
  for (size_t i = 0; i < rest.size(); ++i) {
    const json& row = rest[i];
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number() ||
        !std::isfinite(row[0].get<double>()) || !std::isfinite(row[1].get<double>()))
      throw InputError(f.source(),
                       element_path(rest_path, i) + ": expected [x, y] (finite numbers)");
    piece.rest(static_cast<Eigen::Index>(i), 0) = row[0].get<double>();
    piece.rest(static_cast<Eigen::Index>(i), 1) = row[1].get<double>();
  }
  const int n = static_cast<int>(rest.size());
  const json& triangles = f.raw("triangles");
  const std::string tri_path = f.child_path("triangles");
  if (!triangles.is_array() || triangles.empty())
    f.fail("expected a non-empty array of [a, b, c]", "triangles");
  piece.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const json& row = triangles[t];
    if (!row.is_array() || row.size() != 3)
      throw InputError(f.source(), element_path(tri_path, t) + ": expected [a, b, c]");
    for (int c = 0; c < 3; ++c) {
      check_index(row[c], n, f.source(),
                  element_path(element_path(tri_path, t), static_cast<size_t>(c)));
      piece.triangles(static_cast<Eigen::Index>(t), c) = row[c].get<int>();
    }
  }
  piece.boundary = read_indices(f, "boundary", n);
  if (piece.boundary.size() < 3) f.fail("expected a loop of at least 3 vertices", "boundary");
  if (std::set<int>(piece.boundary.begin(), piece.boundary.end()).size() != piece.boundary.size())
    f.fail("the loop repeats a vertex", "boundary");
  piece.corners = read_indices(f, "corners", n);
  const json& holes = f.raw("holes");
  if (!holes.is_null()) {
    if (!holes.is_array()) f.fail("expected an array of vertex loops", "holes");
    std::set<int> used(piece.boundary.begin(), piece.boundary.end());
    for (size_t h = 0; h < holes.size(); ++h) {
      const std::string path = element_path(f.child_path("holes"), h);
      if (!holes[h].is_array() || holes[h].size() < 3)
        throw InputError(f.source(), path + ": expected a loop of at least 3 vertex indices");
      std::vector<int> loop;
      for (size_t i = 0; i < holes[h].size(); ++i) {
        const json& v = holes[h][i];
        check_index(v, n, f.source(), element_path(path, i));
        if (!used.insert(v.get<int>()).second)
          throw InputError(f.source(), element_path(path, i) + ": vertex " +
                                           std::to_string(v.get<int>()) +
                                           " is already on a boundary loop");
        loop.push_back(v.get<int>());
      }
      piece.holes.push_back(std::move(loop));
    }
  }
  piece.grain = f.vec2("grain");
  if (!piece.grain.allFinite() || piece.grain.norm() == 0.0)
    f.fail("expected a finite, non-zero direction", "grain");
  accept(f, extra);
  f.finish();
  return piece;
}

/// A piece reference and its vertex list (member names "piece", "vertices"), accepting the
/// `extra` keys.
void read_side(JsonFields& f, const Pattern& pattern, const std::vector<std::string>& extra,
               int& piece, std::vector<int>& vertices) {
  accept(f, extra);
  piece = f.integer("piece");
  if (piece < 0 || piece >= static_cast<int>(pattern.pieces.size()))
    f.fail("piece " + std::to_string(piece) + " does not exist (the pattern has " +
               std::to_string(pattern.pieces.size()) + " pieces)",
           "piece");
  vertices = read_indices(f, "vertices",
                          static_cast<int>(pattern.pieces[static_cast<size_t>(piece)].rest.rows()));
}

json side_json(const SeamSide& side) {
  return {{"piece", side.piece}, {"vertices", side.vertices}};
}

}  // namespace

json pattern_record_json(const Pattern& pattern) {
  json pieces = json::array();
  for (const PatternPiece& p : pattern.pieces)
    pieces.push_back({{"name", p.name},
                      {"rest", record_rows_json(p.rest)},
                      {"triangles", record_rows_json(p.triangles)},
                      {"boundary", p.boundary},
                      {"holes", p.holes},
                      {"corners", p.corners},
                      {"grain", json::array({p.grain.x(), p.grain.y()})}});
  json seams = json::array();
  for (const Seam& s : pattern.seams)
    seams.push_back({{"name", s.name}, {"a", side_json(s.a)}, {"b", side_json(s.b)}});
  json pinned = json::array();
  for (const PinnedBoundary& p : pattern.pinned)
    pinned.push_back({{"name", p.name}, {"piece", p.piece}, {"vertices", p.vertices}});
  return {{"pieces", pieces}, {"seams", seams}, {"pinned", pinned}};
}

Pattern pattern_record_from_json(const json& j, const std::string& source, const std::string& path,
                                 const PatternRecordExtraKeys& extra) {
  if (!j.is_object()) throw InputError(source, path + ": expected a pattern (an object)");
  JsonFields f(j, source, path);
  accept(f, extra.root);
  Pattern pattern;
  std::set<std::string> names;
  for (JsonFields& p : f.objects("pieces", true)) {
    pattern.pieces.push_back(read_piece(p, extra.piece));
    if (!names.insert(pattern.pieces.back().name).second)
      p.fail("a second piece named \"" + pattern.pieces.back().name + "\"", "name");
  }
  if (pattern.pieces.empty()) f.fail("expected at least one piece", "pieces");
  for (JsonFields& s : f.objects("seams", true)) {
    Seam seam;
    seam.name = s.string("name");
    auto a = s.object("a", true);
    read_side(*a, pattern, extra.side, seam.a.piece, seam.a.vertices);
    a->finish();
    auto b = s.object("b", true);
    read_side(*b, pattern, extra.side, seam.b.piece, seam.b.vertices);
    b->finish();
    const size_t na = seam.a.vertices.size(), nb = seam.b.vertices.size();
    if (na != nb || na < 2) {
      std::string what = "the sides have ";
      what += std::to_string(na);
      what += " and ";
      what += std::to_string(nb);
      what += na != nb ? " vertices (different vertex counts)" : " vertices (expected at least 2)";
      s.fail(what);
    }
    accept(s, extra.seam);
    s.finish();
    pattern.seams.push_back(std::move(seam));
  }
  for (JsonFields& p : f.objects("pinned", true)) {
    PinnedBoundary pin;
    pin.name = p.string("name");
    read_side(p, pattern, extra.side, pin.piece, pin.vertices);
    p.finish();
    pattern.pinned.push_back(std::move(pin));
  }
  f.finish();
  return pattern;
}

}  // namespace tightfit
