#include "tightfit/garment/garment.hpp"

#include <algorithm>
#include <numeric>

#include "tightfit/common/error.hpp"

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

}  // namespace

Points2 Garment::rest_positions() const {
  Points2 rest(num_pattern_vertices(), 2);
  for (size_t k = 0; k < pattern.pieces.size(); ++k)
    rest.middleRows(piece_offset[k], pattern.pieces[k].rest.rows()) = pattern.pieces[k].rest;
  return rest;
}

void Garment::set_rest_positions(const Points2& rest) {
  for (size_t k = 0; k < pattern.pieces.size(); ++k)
    pattern.pieces[k].rest = rest.middleRows(piece_offset[k], pattern.pieces[k].rest.rows());
}

std::vector<std::array<int, 2>> Garment::seam_edges() const {
  std::vector<std::array<int, 2>> edges;
  for (const Seam& seam : pattern.seams)
    for (const SeamSide* side : {&seam.a, &seam.b}) {
      const int off = piece_offset[side->piece];
      for (size_t i = 0; i + 1 < side->vertices.size(); ++i)
        edges.push_back({off + side->vertices[i], off + side->vertices[i + 1]});
    }
  return edges;
}

Garment weld_pattern(Pattern pattern) {
  Garment g;
  g.piece_offset.push_back(0);
  for (const auto& piece : pattern.pieces)
    g.piece_offset.push_back(g.piece_offset.back() + static_cast<int>(piece.rest.rows()));
  const int n = g.piece_offset.back();

  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Seam& seam : pattern.seams) {
    check_side(pattern, seam.a, seam.name);
    check_side(pattern, seam.b, seam.name);
    if (seam.a.vertices.size() != seam.b.vertices.size())
      throw InputError("pattern", "seam \"" + seam.name + "\" has " +
                                      std::to_string(seam.a.vertices.size()) +
                                      " vertices on one side and " +
                                      std::to_string(seam.b.vertices.size()) + " on the other");
    for (size_t i = 0; i < seam.a.vertices.size(); ++i) {
      const int a = find_root(parent, g.piece_offset[seam.a.piece] + seam.a.vertices[i]);
      const int b = find_root(parent, g.piece_offset[seam.b.piece] + seam.b.vertices[i]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  g.pattern_to_garment.assign(n, -1);
  std::vector<int> id_of_root(n, -1);
  for (int i = 0; i < n; ++i) {
    const int r = find_root(parent, i);
    if (id_of_root[r] < 0) id_of_root[r] = g.num_garment_vertices++;
    g.pattern_to_garment[i] = id_of_root[r];
  }

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
  g.pattern = std::move(pattern);
  return g;
}

}  // namespace tightfit
