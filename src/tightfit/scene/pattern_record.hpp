#pragma once
/// The complete, lossless JSON form of a Pattern, saved where a garment's pattern can no
/// longer be rebuilt from its scene (a pattern remeshed during optimization): in the
/// run state (state.json) and the optimization checkpoint. weld_pattern rebuilds the
/// garment from it.
///
/// {"pieces": [{"name", "rest": [[x, y], ...] (m, n×2), "triangles": [[a, b, c], ...],
///              "boundary": [v, ...], "corners": [v, ...], "grain": [gx, gy]}],
///  "seams": [{"name", "a": {"piece", "vertices": [v, ...]}, "b": {...}}],
///  "pinned": [{"name", "piece", "vertices": [v, ...]}]}
/// Piece references are indices into "pieces", vertices piece-local. Doubles are written
/// in round-trip form, so a read pattern is bit-identical to the written one. It is also
/// the core of pieces.json (patterns/json.hpp), which adds derived keys beside these.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/garment/pattern.hpp"

namespace tightfit {

/// The JSON form of `pattern` described above.
nlohmann::json pattern_record_json(const Pattern& pattern);

/// Keys a file may carry beside a pattern's own (data its writer derives from the
/// pattern, such as pieces.json's outlines): pattern_record_from_json accepts and
/// ignores them.
struct PatternRecordExtraKeys {
  std::vector<std::string> root;   ///< beside "pieces", "seams" and "pinned"
  std::vector<std::string> piece;  ///< in each piece
  std::vector<std::string> seam;   ///< in each seam
  std::vector<std::string> side;   ///< in each seam side and each pinned boundary
};

/// Reads a pattern written by pattern_record_json (object `j` at JSON pointer `path` of
/// the file `source`; `path` is "" for a document's root), accepting the `extra` keys. InputError
/// names `source` and the JSON path of the first problem: a missing, unknown or mistyped field; a
/// piece with an empty or repeated name, fewer than 3 vertices, non-finite positions, no triangles,
/// a triangle, boundary or corner index out of range, a boundary loop with fewer than 3 or repeated
/// vertices, a zero or non-finite grain; a seam or pinned boundary naming a missing piece or a
/// vertex out of range; seam sides of different lengths or shorter than 2.
Pattern pattern_record_from_json(const nlohmann::json& j, const std::string& source,
                                 const std::string& path, const PatternRecordExtraKeys& extra = {});

}  // namespace tightfit
