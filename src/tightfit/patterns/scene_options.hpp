#pragma once
/// The pattern export options of a run: the scene's "patterns" section plus what only
/// the garment on the body tells (which seams are at the back, which end of a seam is
/// up) and the label texts (style, size, fabric, designed stretch, date). The pattern
/// writers stay 2D: everything 3D is decided here.
#include <array>
#include <map>
#include <string>

#include "tightfit/garment/garment.hpp"
#include "tightfit/scene/pattern_export_options.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {

/// Front direction of the body (unit), or zero when it has none: bodies from mesh
/// files are in tightfit's body frame and face +z (MakeHuman bodies, rigs); generated
/// cylinders and spheres have no front.
Vec3 body_front_direction(const BodySpec& spec);

/// Notch style per seam from 3D: Double for a back seam — the garment surface along the
/// seam (its area-weighted normal at `positions`, garment vertices × 3, m, oriented so
/// that the garment's triangles face away from its centroid on the whole) faces more
/// than 60° away from `front` —, Single
/// otherwise (front seams, and side seams and inseams, which face sideways); all Single
/// when `front` is zero.
std::map<std::string, NotchStyle> classify_seam_notches(const Garment& garment,
                                                        const Points3& positions,
                                                        const Vec3& front);

/// Per seam: true when its sides' last vertices are higher along `up` than their first
/// ones, false when lower. Seams whose ends differ in height by less than `min_rise` (m)
/// are left out (no "top" mark on a horizontal seam).
std::map<std::string, bool> seam_upper_ends(const Garment& garment, const Points3& positions,
                                            const Vec3& up, double min_rise = 0.01);

/// The worn stretch of the pattern's axes on the fitted garment (`positions`, garment
/// vertices × 3, m): across the grain (course, piece x) and along it (wale, piece y), each
/// the [5th, 95th] percentile over the pattern's triangles weighted by rest area.
struct GrainStretchRanges {
  std::array<double, 2> course = {0.0, 0.0};
  std::array<double, 2> wale = {0.0, 0.0};
};
GrainStretchRanges grain_stretch_ranges(const Garment& garment, const Points3& positions);

/// The export options of a run of `scene` whose garment is at `positions`: the scene's
/// "patterns" section (seam names checked against the garment: InputError naming the
/// scene file and JSON path), back seams double-notched (classify_seam_notches; an
/// explicit "notches" rule wins), "top" marks from the body's up direction (none on a
/// sphere), and the label: style ("patterns.style", default the scene file's stem), size
/// ("patterns.size", default the body mesh file's stem or "cylinder"/"sphere"), fabric
/// E (before relaxation) and thickness — for a measured knit its name, thickness and the
/// worn course and wale stretch ranges (grain_stretch_ranges) —, the stretch range of the scene's
/// optimize objectives "stretch" or "directional_stretch" (min default 1, max when given), and
/// `date` ("YYYY-MM-DD").
PatternExportOptions scene_pattern_export_options(const SceneSpec& scene, const Garment& garment,
                                                  const Points3& positions,
                                                  const std::string& date);

}  // namespace tightfit
