#pragma once
/// Binary glTF 2.0 (.glb) export of the fit for any 3D viewer: the deformed body
/// (grey, smooth vertex normals) and the garment coloured by the maps of the fit.
///
/// Frame: metres, y up, as glTF requires. Every position and normal is turned by the
/// rotation that takes the body's up direction (FitView::up; glb_rotation) onto +y:
/// for a body in tightfit's body frame (MakeHuman bodies, scans: y up) that is the
/// identity, a generated cylinder (a limb or a torso along its axis, z by default)
/// stands upright instead of showing its end. `asset.extras.scene_up` records the
/// direction that was turned onto +y.
///
/// The garment's vertices are split per face (3 per triangle) so that each face shows
/// its own colour, with NORMAL the garment's smooth (area-weighted) vertex normal at
/// each corner, turned away from the body where FitView::garment_normals says where
/// that is. Colour maps: COLOR_0 holds the chosen colouring (default: max principal
/// stretch), COLOR_1, COLOR_2, … the other standard maps the fit has (min stretch,
/// pressure in mmHg, regime; fit_colormap.hpp), each colormap(t) converted from sRGB to
/// linear light as glTF requires, with t = (value - lo) / (hi - lo) clamped to [0, 1]
/// (range rule in fit_colormap.hpp). Viewers draw COLOR_0 (three.js, the Khronos sample
/// viewer); Blender's importer reads the COLOR_n sets as colour attributes to pick in
/// the shader or the viewport; three.js keeps them as geometry attributes (color,
/// color_1, …); and, for viewers that draw only COLOR_0,
/// every further map is also a glTF scene of its own ("map: Pressure", sharing the
/// geometry's accessors) that the viewer's scene list switches to. Each set's field,
/// unit, colour map, range and attribute are in the garment mesh's
/// `extras.color_sets` and in `asset.extras.color_sets` (with its scene);
/// `extras.coloring` is COLOR_0's. A fit with poses gets one node per pose ("pose NAME":
/// the posed body and garment, the garment coloured by the tangential force above the
/// friction limit in N, one range for all poses), each in a scene of its own after the
/// default scene "fit" and the map scenes.
#include <filesystem>

#include "tightfit/report/fit_colormap.hpp"
#include "tightfit/report/fit_view.hpp"

namespace tightfit {

struct GlbOptions {
  /// Field to colour the garment by; default max principal stretch (viridis).
  FieldColoring coloring = standard_colorings().front();
  bool include_body = true;  ///< also write the body (when it has faces)
  /// Also the other standard colourings the fit has a scalar field for (COLOR_1, … and
  /// a scene per map); false: COLOR_0 only.
  bool all_maps = true;
};

/// The rotation the glb applies: the shortest turn taking `up` (any length > 0) onto
/// +y; the identity for a zero or non-finite `up`.
Mat3 glb_rotation(const Vec3& up);

/// Writes `view` as .glb to `path` atomically and returns the coloring used (with the
/// range). InputError naming `path` for an invalid view or a missing/vector field.
ResolvedColoring write_fit_glb(const std::filesystem::path& path, const FitView& view,
                               const GlbOptions& options = {});

}  // namespace tightfit
