#pragma once
/// Comparisons of two patterns: whether they are meshed alike, and whether a pattern
/// saved in a run's files (scene/pattern_record.hpp) belongs to a scene's pattern.
#include <string>

#include "tightfit/garment/pattern.hpp"

namespace tightfit {

/// True when both patterns have the same pieces (names, vertex counts, triangles,
/// boundary loops, corners), seams and pinned boundaries: rest positions and grain
/// aside, the same garment topology.
bool same_pattern_meshes(const Pattern& a, const Pattern& b);

/// Checks that `saved`, a pattern saved in a run state or checkpoint (at JSON pointer
/// `path` of the file `source`), belongs to the scene's pattern `scene`: the same pieces
/// (names), seams (names and the pieces they join) and pinned boundaries (names and
/// pieces); the meshes may differ (remeshing changes only them). InputError naming
/// `source` and the JSON path of the first difference, with `hint` appended (e.g.
/// " (the scene or its files changed since the run?)").
void check_saved_pattern(const Pattern& saved, const Pattern& scene, const std::string& source,
                         const std::string& path, const std::string& hint);

}  // namespace tightfit
