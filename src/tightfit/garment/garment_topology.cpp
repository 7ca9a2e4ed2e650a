#include "tightfit/garment/garment_topology.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void check_side(const Pattern& p, const SeamSide& side, const std::string& seam) {
  if (side.piece < 0 || side.piece >= static_cast<int>(p.pieces.size()))
    throw InputError("pattern", "seam \"" + seam + "\" names piece " + std::to_string(side.piece) +
                                    ", which does not exist");
  const auto n = p.pieces[side.piece].rest.rows();
  for (int v : side.vertices)
    if (v < 0 || v >= n)
      throw InputError("pattern", "seam \"" + seam + "\" names vertex " + std::to_string(v) +
                                      " of piece \"" + p.pieces[side.piece].name +
                                      "\", which has " + std::to_string(n) + " vertices");
}

std::vector<int> piece_offsets(const Pattern& pattern) {
  std::vector<int> offset{0};
  for (const auto& piece : pattern.pieces)
    offset.push_back(offset.back() + static_cast<int>(piece.rest.rows()));
  return offset;
}

void check_seams(const Pattern& pattern) {
  for (const Seam& seam : pattern.seams) {
    check_side(pattern, seam.a, seam.name);
    check_side(pattern, seam.b, seam.name);
    if (seam.a.vertices.size() != seam.b.vertices.size())
      throw InputError("pattern", "seam \"" + seam.name + "\" has " +
                                      std::to_string(seam.a.vertices.size()) +
                                      " vertices on one side and " +
                                      std::to_string(seam.b.vertices.size()) + " on the other");
  }
}

/// Union-find over the seam vertex pairs: garment vertex ids in order of first appearance.
std::vector<int> weld_by_seams(const Pattern& pattern, const std::vector<int>& offset,
                               int& num_garment_vertices) {
  const int n = offset.back();
  std::vector<int> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (const Seam& seam : pattern.seams)
    for (size_t i = 0; i < seam.a.vertices.size(); ++i) {
      const int a = find_root(parent, offset[seam.a.piece] + seam.a.vertices[i]);
      const int b = find_root(parent, offset[seam.b.piece] + seam.b.vertices[i]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> to_garment(static_cast<size_t>(n), -1);
  std::vector<int> id_of_root(static_cast<size_t>(n), -1);
  num_garment_vertices = 0;
  for (int i = 0; i < n; ++i) {
    const int r = find_root(parent, i);
    if (id_of_root[r] < 0) id_of_root[r] = num_garment_vertices++;
    to_garment[i] = id_of_root[r];
  }
  return to_garment;
}

/// Throws InputError(source, …) unless `map` has one garment vertex in [0, num_garment)
/// for each of the num_pattern pattern vertices.
void check_vertex_map(const std::string& source, const std::vector<int>& map,
                      Eigen::Index num_pattern, int num_garment) {
  if (static_cast<Eigen::Index>(map.size()) != num_pattern)
    throw InputError(source, "the pattern-to-garment vertex map has " + std::to_string(map.size()) +
                                 " entries for " + std::to_string(num_pattern) +
                                 " pattern vertices");
  for (std::size_t p = 0; p < map.size(); ++p)
    if (map[p] < 0 || map[p] >= num_garment)
      throw InputError(source, "pattern vertex " + std::to_string(p) + " maps to garment vertex " +
                                   std::to_string(map[p]) + " outside [0, " +
                                   std::to_string(num_garment) + ")");
}

void collect_triangles(const Pattern& pattern, GarmentTopology& g) {
  int num_triangles = 0;
  for (const auto& piece : pattern.pieces)
    num_triangles += static_cast<int>(piece.triangles.rows());
  g.pattern_triangles.resize(num_triangles, 3);
  g.garment_triangles.resize(num_triangles, 3);
  int t = 0;
  for (size_t k = 0; k < pattern.pieces.size(); ++k) {
    const auto& piece = pattern.pieces[k];
    for (Eigen::Index f = 0; f < piece.triangles.rows(); ++f, ++t) {
      for (int c = 0; c < 3; ++c) {
        const int local = piece.triangles(f, c);
        if (local < 0 || local >= piece.rest.rows())
          throw InputError("pattern", "piece \"" + piece.name + "\" has a triangle with vertex " +
                                          std::to_string(local) + " out of range");
        g.pattern_triangles(t, c) = g.piece_offset[k] + local;
        g.garment_triangles(t, c) = g.pattern_to_garment[g.piece_offset[k] + local];
      }
      g.triangle_piece.push_back(static_cast<int>(k));
    }
  }
}

void collect_seam_edges(const Pattern& pattern, GarmentTopology& g) {
  std::vector<std::vector<int>> sides;  // in global pattern-vertex indices
  for (const Seam& seam : pattern.seams)
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      std::vector<int>& line = sides.emplace_back();
      for (int v : side->vertices) line.push_back(g.piece_offset[side->piece] + v);
    }
  g.seam_edges = polyline_edges(sides);
}

void collect_pinned(const Pattern& pattern, GarmentTopology& g) {
  for (const PinnedBoundary& pin : pattern.pinned) {
    if (pin.piece < 0 || pin.piece >= static_cast<int>(pattern.pieces.size()))
      throw InputError("pattern",
                       "pinned boundary \"" + pin.name + "\" names a piece that does not exist");
    for (int v : pin.vertices) {
      if (v < 0 || v >= pattern.pieces[pin.piece].rest.rows())
        throw InputError("pattern",
                         "pinned boundary \"" + pin.name + "\" names a vertex out of range");
      g.pinned.push_back(g.pattern_to_garment[g.piece_offset[pin.piece] + v]);
    }
  }
  std::sort(g.pinned.begin(), g.pinned.end());
  g.pinned.erase(std::unique(g.pinned.begin(), g.pinned.end()), g.pinned.end());
}

}  // namespace

std::vector<std::array<int, 2>> polyline_edges(const std::vector<std::vector<int>>& polylines) {
  std::vector<std::array<int, 2>> edges;
  for (const auto& line : polylines)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) edges.push_back({line[i], line[i + 1]});
  return edges;
}

int GarmentTopology::piece_of(int pattern_vertex) const {
  return static_cast<int>(
      std::upper_bound(piece_offset.begin(), piece_offset.end(), pattern_vertex) -
      piece_offset.begin() - 1);
}

namespace {

/// The pieces (by name, sorted, without repetition) of the triangles `faces`.
std::string piece_names(const Pattern& pattern, const GarmentTopology& g,
                        const std::vector<int>& faces) {
  std::vector<std::string> names;
  for (int f : faces)
    names.push_back(
        pattern.pieces[static_cast<size_t>(g.triangle_piece[static_cast<size_t>(f)])].name);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// Throws InputError (source "pattern") when the seams weld two corners of one triangle
/// together or give an edge more than two triangles (the welded garment is then no
/// surface: no shape operator, no pressure), naming the pieces where it happens.
void check_welded_surface(const Pattern& pattern, const GarmentTopology& g) {
  for (Eigen::Index f = 0; f < g.garment_triangles.rows(); ++f) {
    const auto c = g.garment_triangles.row(f);
    if (c(0) == c(1) || c(1) == c(2) || c(2) == c(0))
      throw InputError("pattern", "the seams weld two corners of a triangle of piece " +
                                      piece_names(pattern, g, {static_cast<int>(f)}) +
                                      " into one garment vertex");
  }
  const SurfaceTopology surface(g.garment_triangles, g.num_garment_vertices);
  const std::vector<int> bad = surface.non_manifold_edges();
  if (bad.empty()) return;
  const std::array<int, 2> ends = surface.edge_vertices(bad.front());
  throw InputError("pattern", "the welded garment has " + std::to_string(bad.size()) +
                                  " edges with more than two triangles (the first between "
                                  "garment vertices " +
                                  std::to_string(ends[0]) + " and " + std::to_string(ends[1]) +
                                  ", in pieces " +
                                  piece_names(pattern, g, surface.edge_all_faces(bad.front())) +
                                  "): two pieces are joined along the same pair of seam "
                                  "vertices by more than their seam");
}

/// The topology of a pattern whose seams were checked and whose vertex map is valid.
GarmentTopology assemble_topology(const Pattern& pattern, std::vector<int> offset,
                                  std::vector<int> pattern_to_garment, int num_garment_vertices) {
  GarmentTopology g;
  g.piece_offset = std::move(offset);
  g.pattern_to_garment = std::move(pattern_to_garment);
  g.num_garment_vertices = num_garment_vertices;
  collect_triangles(pattern, g);
  collect_seam_edges(pattern, g);
  collect_pinned(pattern, g);
  check_welded_surface(pattern, g);
  return g;
}

}  // namespace

GarmentTopology weld_topology(const Pattern& pattern, std::vector<int> pattern_to_garment,
                              int num_garment_vertices) {
  std::vector<int> offset = piece_offsets(pattern);
  check_seams(pattern);
  check_vertex_map("pattern", pattern_to_garment, offset.back(), num_garment_vertices);
  return assemble_topology(pattern, std::move(offset), std::move(pattern_to_garment),
                           num_garment_vertices);
}

GarmentTopology weld_topology(const Pattern& pattern) {
  std::vector<int> offset = piece_offsets(pattern);
  check_seams(pattern);
  int num_garment_vertices = 0;
  std::vector<int> to_garment = weld_by_seams(pattern, offset, num_garment_vertices);
  return assemble_topology(pattern, std::move(offset), std::move(to_garment), num_garment_vertices);
}

GarmentTopology one_piece_topology(const std::string& source, Eigen::Index num_pattern_vertices,
                                   Triangles triangles, std::vector<std::array<int, 2>> seam_edges,
                                   std::vector<int> pattern_to_garment, int num_garment_vertices) {
  check_vertex_map(source, pattern_to_garment, num_pattern_vertices, num_garment_vertices);
  const auto out_of_range = [&](int v) { return v < 0 || v >= num_pattern_vertices; };
  for (Eigen::Index e = 0; e < triangles.rows(); ++e)
    for (int k = 0; k < 3; ++k)
      if (out_of_range(triangles(e, k)))
        throw InputError(source, "triangle " + std::to_string(e) + " has pattern vertex " +
                                     std::to_string(triangles(e, k)) + " outside [0, " +
                                     std::to_string(num_pattern_vertices) + ")");
  for (std::size_t s = 0; s < seam_edges.size(); ++s)
    for (int v : seam_edges[s])
      if (out_of_range(v))
        throw InputError(source, "seam edge " + std::to_string(s) + " has pattern vertex " +
                                     std::to_string(v) + " outside [0, " +
                                     std::to_string(num_pattern_vertices) + ")");
  GarmentTopology g;
  g.piece_offset = {0, static_cast<int>(num_pattern_vertices)};
  g.garment_triangles.resize(triangles.rows(), 3);
  for (Eigen::Index e = 0; e < triangles.rows(); ++e)
    for (int k = 0; k < 3; ++k)
      g.garment_triangles(e, k) = pattern_to_garment[static_cast<std::size_t>(triangles(e, k))];
  g.triangle_piece.assign(static_cast<std::size_t>(triangles.rows()), 0);
  g.pattern_triangles = std::move(triangles);
  g.seam_edges = std::move(seam_edges);
  g.pattern_to_garment = std::move(pattern_to_garment);
  g.num_garment_vertices = num_garment_vertices;
  return g;
}

}  // namespace tightfit
