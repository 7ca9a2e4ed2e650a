#pragma once
/// Binary glTF 2.0 (.glb) export of the fit for any 3D viewer: the deformed body
/// (grey, smooth vertex normals) and the garment coloured by one face field.
///
/// Coordinates are written as they are (metres; tightfit's bodies are y up like glTF).
/// The garment's vertices are split per face (3 per triangle) so that each face shows
/// its own colour; COLOR_0 holds colormap(t) converted from sRGB to linear light as
/// glTF requires, with t = (value - lo) / (hi - lo) clamped to [0, 1] (range rule in
/// fit_colormap.hpp). The field, unit, colour map and range are stored in the
/// garment mesh's `extras` and in `asset.extras.coloring`. A fit with poses gets one
/// node per pose ("pose NAME": the posed body and garment, the garment coloured by the
/// tangential force above the friction limit in N, one range for all poses), each in a
/// glTF scene of its own after the default scene "fit".
#include <filesystem>

#include "tightfit/io/fit_colormap.hpp"
#include "tightfit/io/fit_view.hpp"

namespace tightfit {

struct GlbOptions {
  /// Field to colour the garment by; default max principal stretch (viridis).
  FieldColoring coloring = standard_colorings().front();
  bool include_body = true;  ///< also write the body (when it has faces)
};

/// Writes `view` as .glb to `path` atomically and returns the coloring used (with the
/// range). InputError naming `path` for an invalid view or a missing/vector field.
ResolvedColoring write_fit_glb(const std::filesystem::path& path, const FitView& view,
                               const GlbOptions& options = {});

}  // namespace tightfit
