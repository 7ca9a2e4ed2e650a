#pragma once
/// A grading nest: the same pattern pieces of every size drawn on top of each other, as
/// a pattern maker checks a graded set (the sizes step evenly, the seams stay matched).
/// Each piece of each size is turned so its grain line points up (+y) and moved so its
/// alignment point lies at the origin: its area centroid (the grain lines of all sizes
/// then lie on one line) or the end of a chosen seam (where notch 0 of that seam sits).
#include <filesystem>
#include <string>
#include <vector>

#include "tightfit/garment/pattern.hpp"

namespace tightfit {

/// One size of the nest: its name (a body) and its pattern.
struct NestSize {
  std::string name;
  const Pattern* pattern = nullptr;
};

struct Nest {
  /// Every piece of every size, aligned; named "PIECE/SIZE". Its seams and pinned
  /// boundaries are those of each size, named "SEAM/SIZE", so every size has its notches.
  Pattern pattern;
  std::vector<int> group;                ///< per nest piece: its piece (index into piece_names)
  std::vector<int> size;                 ///< per nest piece: its size (index into sizes)
  std::vector<std::string> piece_names;  ///< the nested pieces, in the first size's order
  std::vector<std::string> size_names;
  std::string alignment;  ///< "centroid" or "seam SEAM"
};

/// Builds the nest of `sizes` (at least one). Pieces are matched by name: the pieces of
/// the first size, in its order; a size without one of them just has none in that
/// group. `seam` empty: pieces aligned at their area centroid; otherwise at the start of
/// seam `seam` (its first vertex on the piece; pieces the seam does not touch are
/// aligned at their centroid). InputError (source "--nest-seam") when no piece of the
/// first size lies on `seam`.
Nest make_nest(const std::vector<NestSize>& sizes, const std::string& seam);

/// Writes the nest's exports into `folder` (each atomically): nest.svg (1:1), nest.pdf
/// (one full-size page) and nest.dxf (AAMA/ASTM D6673), each group of pieces at one
/// spot, without piece labels (they would lie on top of each other; the DXF names every
/// piece). Returns the file names.
std::vector<std::string> write_nest_files(const std::filesystem::path& folder, const Nest& nest);

}  // namespace tightfit
