#pragma once
/// How a garment is laid out on a body, as the user writes it (JSON). Two forms:
///
/// Rules (panels cut from the body surface by planes):
/// ```json
/// {
///   "region":   [{"name": "waist", "point": [0, 1.0, 0], "normal": [0, -1, 0]}],
///   "dividers": [{"name": "sagittal", "point": [0, 0, 0], "normal": [1, 0, 0]}],
///   "panels":   [{"name": "left", "sides": ["+sagittal"]},
///                {"name": "right", "sides": ["-sagittal"]}],
///   "pinned":   [{"name": "waistband", "on_plane": "waist"},
///                {"name": "cuff", "nearest": [0.1, 0.1, 0.0]}],
///   "seam_tolerance": 0.05
/// }
/// ```
/// * `region`: the garment covers the part of the body surface on the side each region
///   plane's normal points to (all planes at once). No planes: the whole surface.
/// * `dividers`: named planes that split the region into panels.
/// * `panels`: a panel is the part of the region on the given side ("+name": the side
///   the normal points to, "-name": the other) of each listed divider; dividers it does
///   not list do not split it. Every face of the region must lie in exactly one panel.
/// * Every plane cuts the body surface with new vertices exactly on it, so panel
///   boundaries are clean polylines. Planes must cross the surface, not lie in it: a
///   plane that misses the body is an input error naming it (layout_anchors.hpp).
///
/// Anchored on the skeleton (layouts that transfer between the bodies of one rig;
/// resolved on each body by garment/layout_anchors.hpp, with the scene's `"rig"`):
/// ```json
/// {"name": "knee", "point": {"bone": "lowerleg01.L", "at": 0.5}, "normal": "along_bone"}
/// {"name": "waist", "point": {"bone": "spine05", "at": 0}, "normal": "down"}
/// {"name": "side", "point": {"bone": "upperarm02.L", "at": 0.5},
///  "normal": {"along_bone": "lowerarm01.L", "reversed": true}}
/// {"name": "left_arm", "bones": ["upperarm01.L", "upperarm02.L", "lowerarm01.L"]}
/// ```
/// * `point`: [x, y, z] (m), or `{"bone": NAME, "at": t}`: head + t (tail − head) of
///   the bone, 0 ≤ t ≤ 1.
/// * `normal`: [x, y, z]; a body axis `"left"` (+x), `"right"`, `"up"` (+y), `"down"`,
///   `"front"` (+z), `"back"`; `"along_bone"` / `"-along_bone"`: head → tail of the
///   point's bone (or tail → head); `{"along_bone": NAME, "reversed": false}`: of another
///   bone.
/// * `bones` instead of `point` and `normal` (region planes and dividers): a bone region,
///   cut along the ½ iso-line of the bones' summed, normalized skin weight carried to the
///   body surface by position (body/skin_transfer.hpp); its "+" side is the surface the
///   bones dominate (summed weight ≥ ½), e.g. panel sides ["+left_thigh", "+front"].
///   As a region plane it keeps that surface, and `"on_plane"` pins its iso-line.
/// * Pins' inline planes (`"on_plane": {...}`) may be anchored; they are not bone regions.
/// * `"local": true` on a region plane or divider: only the plane's cut loop nearest to
///   its point counts (a cuff around the wrist, not the legs behind the same plane); the
///   surface beyond that loop is its "−" side, everything else its "+" side.
///
/// Mesh (panels drawn by hand, e.g. in Blender): `{"mesh": "layout.obj", "pinned": [...]}`,
/// an OBJ lying on the body with one group (`g`/`o`) per panel; the path is relative to
/// the spec file. Coincident vertices of different groups are welded (see
/// `weld_tolerance`), so shared panel edges become seams.
///
/// Both forms:
/// * `pinned`: open garment boundaries held on the body. `"on_plane": "name"` pins every
///   open boundary edge lying on that region plane; `"on_plane": {"point", "normal"}`
///   every open boundary edge within `plane_tolerance` of that plane; `"nearest": [x,y,z]`
///   pins the whole open boundary loop nearest to the point (within `max_distance` m if
///   given).
/// * `area_tolerance`: the largest accepted relative difference between a panel's
///   flattened and 3D areas (default 0.5 = 50 %; a hemisphere flattens with about 32 %):
///   beyond it the panel is too curved to be one piece.
/// * `stray_part_fraction`: a part of a panel cut off from the rest by dividers that
///   graze the body, smaller than this share of the panel's area (default 0.05; 0: none),
///   joins the neighbouring panel it shares the longest edge with, with a warning.
/// * `seam_tolerance`: the largest accepted relative length difference of the two sides
///   of a seam after flattening, before scale-down (default 0.05 = 5 %); differences
///   below one pattern edge length are accepted whatever their share.
/// * `description`: free text, ignored.
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tightfit/body/skeleton_anchor.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// An oriented plane: points x with normal·(x − point) > 0 are on its "+" side. Or a
/// bone region (`bones` not empty): its "+" side is where the bones' summed skin weight
/// is ≥ ½. Anchors and bone regions are resolved on a body by
/// garment/layout_anchors.hpp before cutting.
struct LayoutPlane {
  std::string name;
  Vec3 point = Vec3::Zero();                ///< a point on the plane (m)
  Vec3 normal = Vec3::UnitY();              ///< unit normal
  std::string source_path;                  ///< JSON path, for error messages
  std::optional<BoneAnchor> anchor;         ///< unresolved: `point` comes from the skeleton
  std::optional<BoneDirection> along_bone;  ///< unresolved: `normal` comes from the skeleton
  std::vector<std::string> bones;           ///< a bone region instead of a plane
  /// A local plane: only its cut loop nearest to `point` counts, and its "−" side is
  /// the surface beyond that loop (a sleeve's cuff at the wrist, which must not cut the
  /// legs that lie behind the same plane in an A-pose).
  bool local = false;
  /// A resolved bone region or local plane: per vertex of the body surface it was
  /// resolved on, the bones' summed skin weight minus ½ (dimensionless), or the signed
  /// distance to the plane (m) beyond the loop and its absolute value elsewhere; > 0 on
  /// the "+" side, linear along the edges the cut crosses.
  std::vector<double> field;

  bool is_bone_region() const { return !bones.empty(); }
  /// Whether the plane is cut along a per-vertex field (bone regions, local planes).
  bool is_field() const { return is_bone_region() || local; }
  /// Whether resolving needs the skeleton or skin weights: an anchor, a bone direction
  /// or a bone region not yet resolved.
  bool needs_rig() const { return anchor || along_bone || (is_bone_region() && field.empty()); }
  /// Signed distance (m) of x from the plane, positive on the "+" side (planes only).
  double distance(const Vec3& x) const { return normal.dot(x - point); }
};

/// An ellipsoidal opening cut out of a rules layout: the surface where
/// Σ_k ((x_k − center_k) / radii_k)² < 1 is removed.
struct LayoutOpening {
  std::string name;
  Vec3 center = Vec3::Zero();  ///< m
  Vec3 radii = Vec3::Ones();   ///< semi-axes along the body's x, y, z (m, > 0)
  std::string source_path;     ///< JSON path, for error messages

  /// A signed, length-like level function: (|D⁻¹(x − center)| − 1) · min(radii),
  /// negative inside, zero on the ellipsoid, ≈ the distance (m) near it.
  double level(const Vec3& x) const {
    return ((x - center).cwiseQuotient(radii).norm() - 1.0) * radii.minCoeff();
  }
  /// Gradient of level() at x (x ≠ center).
  Vec3 level_gradient(const Vec3& x) const {
    const Vec3 y = (x - center).cwiseQuotient(radii);
    const double r = y.norm();
    return r > 0 ? Vec3(y.cwiseQuotient(radii) / r * radii.minCoeff()) : Vec3::Zero();
  }
};

/// A panel of a rules layout: the region part on the given sides of some dividers.
struct PanelRule {
  std::string name;
  /// (divider index into LayoutSpec::dividers, side +1 or −1).
  std::vector<std::pair<int, int>> sides;
  std::string source_path;
};

/// An open boundary of the garment to pin on the body.
struct PinRule {
  enum class Kind { kOnRegionPlane, kOnPlane, kNearest };
  std::string name;
  Kind kind = Kind::kNearest;
  int region_plane = -1;      ///< kOnRegionPlane: index into LayoutSpec::region
  LayoutPlane plane;          ///< kOnPlane: the plane
  Vec3 point = Vec3::Zero();  ///< kNearest: the point (m)
  double max_distance = std::numeric_limits<double>::infinity();  ///< kNearest (m)
  std::string source_path;
};

/// A parsed layout. Exactly one of the two forms: rules (mesh_file empty) or mesh.
struct LayoutSpec {
  std::string source;  ///< spec file name (or scene file) for errors
  std::string path;    ///< JSON path of the spec inside `source`
  std::vector<LayoutPlane> region;
  std::vector<LayoutPlane> dividers;
  std::vector<PanelRule> panels;
  std::vector<LayoutOpening> openings;  ///< rules layouts only
  std::string mesh_file;                ///< OBJ layout (resolved path); empty for rules
  std::vector<PinRule> pins;
  double seam_tolerance = 0.05;  ///< relative seam side length difference
  double area_tolerance = 0.5;   ///< relative flattened area difference of a panel
  double stray_part_fraction =
      0.05;                       ///< stray parts below this share of their panel join a neighbour
  double plane_tolerance = 1e-4;  ///< m, for "on_plane" with an inline plane
  double weld_tolerance = 1e-6;   ///< m, coincident OBJ vertices are welded

  bool is_mesh_layout() const { return !mesh_file.empty(); }
  /// JSON path of the first plane that needs the skeleton or skin weights (see
  /// LayoutPlane::needs_rig), empty when none does.
  std::string first_rig_use() const;
};

/// Parses a layout spec object. `base_dir` resolves a relative "mesh" path.
/// Throws InputError naming `fields.source()` and the JSON path of the problem.
LayoutSpec parse_layout_spec(JsonFields& fields, const std::string& base_dir);

/// Reads and parses a layout spec JSON file.
LayoutSpec read_layout_spec(const std::string& file);

}  // namespace tightfit
