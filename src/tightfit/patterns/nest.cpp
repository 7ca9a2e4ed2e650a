#include "tightfit/patterns/nest.hpp"

#include <cmath>
#include <map>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/patterns/dxf.hpp"
#include "tightfit/patterns/pdf.hpp"
#include "tightfit/patterns/svg.hpp"

namespace tightfit {
namespace {

/// Area centroid of a piece's mesh (m).
Vec2 area_centroid(const PatternPiece& piece) {
  Vec2 sum = Vec2::Zero();
  double area = 0.0;
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    const Vec2 a = piece.rest.row(piece.triangles(t, 0)).transpose();
    const Vec2 b = piece.rest.row(piece.triangles(t, 1)).transpose();
    const Vec2 c = piece.rest.row(piece.triangles(t, 2)).transpose();
    const double w = std::abs(signed_area(a, b, c));
    sum += w * (a + b + c) / 3.0;
    area += w;
  }
  return area > 0.0 ? Vec2(sum / area) : Vec2(piece.rest.colwise().mean().transpose());
}

/// The first vertex of seam `seam` on piece `p`, or -1.
int seam_start(const Pattern& pattern, int p, const std::string& seam) {
  for (const Seam& s : pattern.seams) {
    if (s.name != seam) continue;
    if (s.a.piece == p && !s.a.vertices.empty()) return s.a.vertices.front();
    if (s.b.piece == p && !s.b.vertices.empty()) return s.b.vertices.front();
  }
  return -1;
}

/// `piece` turned so that its grain points along +y, with `origin` (in its coordinates
/// before the turn) moved to (0, 0).
PatternPiece aligned(const PatternPiece& piece, const Vec2& origin) {
  const Vec2 g = piece.grain.norm() > 0.0 ? Vec2(piece.grain.normalized()) : Vec2(Vec2::UnitY());
  Eigen::Matrix2d turn;
  turn << g.y(), -g.x(), g.x(), g.y();
  PatternPiece out = piece;
  for (Eigen::Index i = 0; i < out.rest.rows(); ++i)
    out.rest.row(i) = (turn * (piece.rest.row(i).transpose() - origin)).transpose();
  out.grain = Vec2::UnitY();
  return out;
}

}  // namespace

Nest make_nest(const std::vector<NestSize>& sizes, const std::string& seam) {
  if (sizes.empty()) throw InputError("nest", "no size to nest");
  Nest nest;
  nest.alignment = seam.empty() ? "centroid" : "seam " + seam;
  const Pattern& first = *sizes.front().pattern;
  for (const PatternPiece& piece : first.pieces) nest.piece_names.push_back(piece.name);
  if (!seam.empty()) {
    bool found = false;
    for (size_t p = 0; p < first.pieces.size(); ++p)
      found |= seam_start(first, static_cast<int>(p), seam) >= 0;
    if (!found)
      throw InputError("--nest-seam",
                       "no seam \"" + seam + "\" in the pattern of " + sizes.front().name);
  }
  for (size_t s = 0; s < sizes.size(); ++s) {
    const Pattern& pattern = *sizes[s].pattern;
    nest.size_names.push_back(sizes[s].name);
    std::map<int, int> index;  // piece of this size -> nest piece
    for (size_t p = 0; p < pattern.pieces.size(); ++p) {
      const PatternPiece& piece = pattern.pieces[p];
      int group = -1;
      for (size_t g = 0; g < nest.piece_names.size(); ++g)
        if (nest.piece_names[g] == piece.name) group = static_cast<int>(g);
      if (group < 0) continue;
      const int start = seam.empty() ? -1 : seam_start(pattern, static_cast<int>(p), seam);
      const Vec2 origin =
          start >= 0 ? Vec2(piece.rest.row(start).transpose()) : area_centroid(piece);
      PatternPiece moved = aligned(piece, origin);
      moved.name = piece.name + "/" + sizes[s].name;
      index[static_cast<int>(p)] = static_cast<int>(nest.pattern.pieces.size());
      nest.pattern.pieces.push_back(std::move(moved));
      nest.group.push_back(group);
      nest.size.push_back(static_cast<int>(s));
    }
    for (const Seam& original : pattern.seams) {
      if (!index.contains(original.a.piece) || !index.contains(original.b.piece)) continue;
      Seam copy = original;
      copy.name = original.name + "/" + sizes[s].name;
      copy.a.piece = index.at(original.a.piece);
      copy.b.piece = index.at(original.b.piece);
      nest.pattern.seams.push_back(std::move(copy));
    }
    for (const PinnedBoundary& original : pattern.pinned) {
      if (!index.contains(original.piece)) continue;
      PinnedBoundary copy = original;
      copy.name = original.name + "/" + sizes[s].name;
      copy.piece = index.at(original.piece);
      nest.pattern.pinned.push_back(std::move(copy));
    }
  }
  return nest;
}

std::vector<std::string> write_nest_files(const std::filesystem::path& folder, const Nest& nest) {
  PatternExportOptions options;
  options.nest_group = nest.group;
  options.piece_labels = false;
  write_pattern_svg(nest.pattern, options, folder / "nest.svg");
  write_pattern_pdf_full_size(nest.pattern, options, folder / "nest.pdf");
  write_pattern_dxf(nest.pattern, options, folder / "nest.dxf");
  return {"nest.svg", "nest.pdf", "nest.dxf"};
}

}  // namespace tightfit
