#pragma once
/// Options for turning a layout into initial pattern pieces (flatten, scale down, mesh).
///
/// JSON form (all keys optional):
/// ```json
/// {"edge_length": 0.02, "scale": [0.9, 0.9], "grain": [0, 1, 0],
///  "piece_scale": {"left_front": [0.95, 0.77]},
///  "arap_iterations": 200, "smoothing_iterations": 10, "corner_angle_deg": 30,
///  "flatten_limit_surface": true}
/// ```
/// `scale` is [along the grain, across the grain]: the factors by which each flattened
/// piece is shrunk so that the garment starts stretched (e.g. 1/1.3 ≈ 0.77 across the
/// grain for 30 % circumferential stretch on a leg when the grain runs along it).
#include <map>
#include <optional>
#include <string>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/garment/flatten.hpp"

namespace tightfit {

/// Scale-down factors of one piece in its grain frame (dimensionless, > 0).
struct PieceScale {
  double along = 0.9;   ///< along the grain (piece y axis)
  double across = 0.9;  ///< across the grain (piece x axis)
};

struct PatternOptions {
  /// Target edge length of the pattern meshes in the scaled pieces (m).
  double edge_length = 0.02;
  PieceScale scale;                               ///< default for every piece
  std::map<std::string, PieceScale> piece_scale;  ///< per-piece overrides by panel name
  /// Body-space direction that becomes each piece's grain (+y) axis, projected onto the
  /// panel. Without it the grain is the longest principal axis of the flattened piece.
  std::optional<Vec3> grain;
  FlattenOptions flatten;  ///< LSCM + ARAP settings
  /// An open boundary turning by more than this angle (degrees) at a vertex of the
  /// flattened panel keeps that vertex as a piece corner (seam ends always are corners).
  double corner_angle_deg = 30.0;
  int smoothing_iterations = 10;  ///< smoothing steps of the 2D meshes (piece_mesher.hpp)
  /// Move the panel vertices onto the limit surface before flattening, so that the
  /// unscaled pieces fit the surface the garment is embedded in (which lies slightly
  /// inside the control mesh).
  bool flatten_limit_surface = true;

  /// The scale of the piece cut from panel `name`.
  const PieceScale& scale_of(const std::string& name) const {
    auto it = piece_scale.find(name);
    return it == piece_scale.end() ? scale : it->second;
  }
};

/// Parses the JSON form above (strict keys; InputError with file and JSON path).
PatternOptions parse_pattern_options(JsonFields& fields);

}  // namespace tightfit
