#pragma once
/// Skin weights of a rigged body mesh: how much each bone moves each vertex (linear
/// blend skinning's weights), read from a MakeHuman weights file (`.mhw`, JSON:
/// {"weights": {BONE: [[vertex, weight], ...], ...}}, e.g. data/rig/default_weights.mhw)
/// together with the mesh the vertex indices refer to (data/bodies/mh_male_*.obj keep
/// MakeHuman's vertex order). Entries whose vertex index lies beyond the mesh — MakeHuman's
/// helper geometry, absent from our bodies — are skipped. The weights of each vertex are
/// normalized to sum to 1 (the file's are rounded: MakeHuman's sum to 0.95-1.06).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

struct SkinWeights {
  Points3 vertices;  ///< rig mesh vertex positions (m), in the body's frame
  Triangles faces;   ///< rig mesh triangles (for transferring weights by closest point)
  /// Per bone: (vertex, weight) pairs with 0 < weight <= 1, vertex < vertices.rows();
  /// each vertex's weights sum to 1.
  std::map<std::string, std::vector<std::pair<int, double>>> bones;
  std::string source;  ///< the weights file, for messages

  /// Σ_b w_b(v) over the named bones for every rig vertex (n, in [0, 1] for normalized
  /// weights). Throws InputError (source `source`) naming a bone the rig does not have.
  VecX summed(const std::vector<std::string>& names, const std::string& context) const;
};

/// Reads the rig mesh `mesh` (any format read_tri_mesh reads; only its vertices are
/// used) and the weights file `weights`. Throws InputError naming the file: unreadable
/// files, a missing "weights" object, malformed entries, a negative or non-finite
/// weight, a negative vertex index.
SkinWeights read_skin_weights(const std::filesystem::path& mesh,
                              const std::filesystem::path& weights);

}  // namespace tightfit
