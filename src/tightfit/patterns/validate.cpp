#include "tightfit/patterns/validate.hpp"

#include <cmath>
#include <set>
#include <unordered_map>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"

namespace tightfit {
namespace {

std::string piece_tag(const Pattern& pattern, int p) {
  return "piece " + std::to_string(p) + " '" + pattern.pieces[static_cast<size_t>(p)].name + "'";
}

void validate_piece(const Pattern& pattern, int p, const std::string& source,
                    std::set<std::string>& names) {
  const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
  const std::string tag = piece_tag(pattern, p);
  auto fail = [&](const std::string& what) { throw InputError(source, tag + ": " + what); };
  if (piece.name.empty()) throw InputError(source, "piece " + std::to_string(p) + ": empty name");
  if (!names.insert(piece.name).second) fail("duplicate piece name");
  const auto n = static_cast<int>(piece.rest.rows());
  if (n < 3) fail("fewer than 3 vertices (empty piece)");
  if (!piece.rest.allFinite()) fail("non-finite rest position");
  if (piece.triangles.rows() == 0) fail("no triangles");
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = piece.triangles(t, k);
      if (v < 0 || v >= n) {
        fail("triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
             " out of range [0, " + std::to_string(n) + ")");
      }
    }
  }
  if (piece.boundary.size() < 3) fail("boundary loop has fewer than 3 vertices");
  std::set<int> on_boundary;
  for (int v : piece.boundary) {
    if (v < 0 || v >= n) {
      fail("boundary vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(n) +
           ")");
    }
    if (!on_boundary.insert(v).second) fail("boundary loop repeats vertex " + std::to_string(v));
  }
  auto loop_area = [&piece](const std::vector<int>& loop) {
    return polygon_signed_area(
        loop.size(), [&](size_t i) -> Vec2 { return piece.rest.row(loop[i]).transpose(); });
  };
  if (!(loop_area(piece.boundary) > 0.0))
    fail("boundary loop is not counter-clockwise (signed area <= 0)");
  for (size_t h = 0; h < piece.holes.size(); ++h) {
    const std::vector<int>& hole = piece.holes[h];
    const std::string which = "hole " + std::to_string(h) + " ";
    if (hole.size() < 3) fail(which + "has fewer than 3 vertices");
    for (size_t i = 0; i < hole.size(); ++i) {
      const int v = hole[i];
      if (v < 0 || v >= n)
        fail(which + "vertex index " + std::to_string(v) + " out of range [0, " +
             std::to_string(n) + ")");
      if (!on_boundary.insert(v).second)
        fail(which + "repeats vertex " + std::to_string(v) + " of a boundary loop");
    }
    if (!(loop_area(hole) < 0.0)) fail(which + "is not clockwise (signed area >= 0)");
  }
  for (int c : piece.corners) {
    if (!on_boundary.count(c)) fail("corner " + std::to_string(c) + " is not a boundary vertex");
  }
  if (!piece.grain.allFinite() || piece.grain.norm() < 1e-12) fail("grain direction is zero");
}

/// Checks a boundary polyline (seam side or pinned boundary) of piece `p`.
void validate_polyline(const Pattern& pattern, int p, const std::vector<int>& vertices,
                       const std::string& source, const std::string& tag) {
  auto fail = [&](const std::string& what) { throw InputError(source, tag + ": " + what); };
  if (p < 0 || p >= static_cast<int>(pattern.pieces.size())) {
    fail("piece index " + std::to_string(p) + " out of range [0, " +
         std::to_string(pattern.pieces.size()) + ")");
  }
  const PatternPiece& piece = pattern.pieces[static_cast<size_t>(p)];
  const auto n = static_cast<int>(piece.rest.rows());
  // Position of every boundary vertex in its loop (outer loop or a hole).
  const std::vector<std::vector<int>> loops = piece.loops();
  std::unordered_map<int, std::pair<int, int>> loop_position;
  for (size_t l = 0; l < loops.size(); ++l)
    for (size_t i = 0; i < loops[l].size(); ++i)
      loop_position[loops[l][i]] = {static_cast<int>(l), static_cast<int>(i)};
  if (vertices.size() < 2) fail("fewer than 2 vertices");
  const auto first = loop_position.find(vertices.front());
  const int loop = first == loop_position.end() ? 0 : first->second.first;
  const auto m = static_cast<int>(loops[static_cast<size_t>(loop)].size());
  std::unordered_map<int, int> position;
  for (int i = 0; i < m; ++i)
    position[loops[static_cast<size_t>(loop)][static_cast<size_t>(i)]] = i;
  if (static_cast<int>(vertices.size()) > m + 1) fail("longer than the boundary loop");
  int direction = 0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const int v = vertices[i];
    if (v < 0 || v >= n) {
      fail("vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(n) +
           ") of " + piece_tag(pattern, p));
    }
    if (!position.count(v)) {
      fail("vertex " + std::to_string(v) + " is not on the boundary of " + piece_tag(pattern, p));
    }
    if (i == 0) continue;
    const int step = ((position[v] - position[vertices[i - 1]]) % m + m) % m;
    const int d = step == 1 ? 1 : (step == m - 1 ? -1 : 0);
    if (d == 0 || (direction != 0 && d != direction)) {
      fail("vertices " + std::to_string(vertices[i - 1]) + " and " + std::to_string(v) +
           " are not consecutive along the boundary of " + piece_tag(pattern, p));
    }
    direction = d;
  }
}

}  // namespace

void validate_pattern(const Pattern& pattern, const std::string& source) {
  if (pattern.pieces.empty()) throw InputError(source, "pattern has no pieces");
  std::set<std::string> names;
  for (int p = 0; p < static_cast<int>(pattern.pieces.size()); ++p) {
    validate_piece(pattern, p, source, names);
  }
  for (size_t s = 0; s < pattern.seams.size(); ++s) {
    const Seam& seam = pattern.seams[s];
    const std::string tag = "seam " + std::to_string(s) + " '" + seam.name + "'";
    if (seam.a.vertices.size() != seam.b.vertices.size()) {
      throw InputError(source, tag + ": sides have different vertex counts (" +
                                   std::to_string(seam.a.vertices.size()) + " and " +
                                   std::to_string(seam.b.vertices.size()) + ")");
    }
    validate_polyline(pattern, seam.a.piece, seam.a.vertices, source, tag + " side a");
    validate_polyline(pattern, seam.b.piece, seam.b.vertices, source, tag + " side b");
  }
  for (size_t i = 0; i < pattern.pinned.size(); ++i) {
    const PinnedBoundary& pin = pattern.pinned[i];
    validate_polyline(pattern, pin.piece, pin.vertices, source,
                      "pinned boundary " + std::to_string(i) + " '" + pin.name + "'");
  }
}

void validate_export_options(const Pattern& pattern, const PatternExportOptions& options,
                             const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source, "export options: " + what); };
  if (!(options.seam_allowance >= 0.0) || !std::isfinite(options.seam_allowance)) {
    fail("seam allowance must be >= 0");
  }
  if (!(options.mitre_limit >= 1.0)) fail("mitre limit must be >= 1");
  if (!(options.notch_spacing >= 0.0)) fail("notch spacing must be >= 0");
  if (!(options.notch_depth >= 0.0) || !std::isfinite(options.notch_depth))
    fail("notch depth must be >= 0");
  if (!(options.double_notch_gap >= 0.0) || !std::isfinite(options.double_notch_gap))
    fail("double notch gap must be >= 0");
  if (!(options.true_tolerance >= 0.0) || !std::isfinite(options.true_tolerance))
    fail("truing tolerance must be >= 0");
  if (!(options.tile_overlap >= 0.0) || !(options.page_margin >= 0.0)) {
    fail("tile overlap and page margin must be >= 0");
  }
  const PaperSize paper = paper_size(options.paper);
  const double content_mm =
      std::min(paper.width_mm, paper.height_mm) - 2000.0 * options.page_margin;
  if (!(content_mm - 1000.0 * options.tile_overlap > 10.0)) {
    fail("page margin and tile overlap leave no room on the page");
  }
  if (!(options.layout_width > 0.0) || !(options.layout_gap >= 0.0)) {
    fail("layout width must be > 0 and layout gap >= 0");
  }
  std::set<std::string> known;
  for (const Seam& seam : pattern.seams) known.insert(seam.name);
  for (const PinnedBoundary& pin : pattern.pinned) known.insert(pin.name);
  for (const auto& [name, allowance] : options.seam_allowances) {
    if (!known.count(name)) fail("seam allowance given for unknown seam '" + name + "'");
    if (!(allowance >= 0.0) || !std::isfinite(allowance)) {
      fail("seam allowance of '" + name + "' must be >= 0");
    }
  }
  std::set<std::string> seams;
  for (const Seam& seam : pattern.seams) seams.insert(seam.name);
  for (const auto& entry : options.seam_notch_styles)
    if (!seams.count(entry.first)) fail("notch style given for unknown seam '" + entry.first + "'");
  for (const auto& entry : options.seam_last_end_up)
    if (!seams.count(entry.first)) fail("upper end given for unknown seam '" + entry.first + "'");
  std::set<std::string> pieces;
  for (const PatternPiece& piece : pattern.pieces) pieces.insert(piece.name);
  for (const auto& entry : options.piece_notes)
    if (!pieces.count(entry.first)) fail("notes given for unknown piece '" + entry.first + "'");
  for (const auto& [name, quantity] : options.quantities) {
    if (quantity < 1) fail("quantity of '" + name + "' must be >= 1");
  }
  if (!options.nest_group.empty() && options.nest_group.size() != pattern.pieces.size())
    fail("a nest needs one group per piece");
  for (int group : options.nest_group)
    if (group < 0) fail("nest groups must be >= 0");
}

}  // namespace tightfit
