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
///   boundaries are clean polylines. Planes must cross the surface, not lie in it.
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
/// * `seam_tolerance`: the largest accepted relative length difference of the two sides
///   of a seam after flattening, before scale-down (default 0.05 = 5 %).
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// An oriented plane: points x with normal·(x − point) > 0 are on its "+" side.
struct LayoutPlane {
  std::string name;
  Vec3 point = Vec3::Zero();   ///< a point on the plane (m)
  Vec3 normal = Vec3::UnitY(); ///< unit normal
  std::string source_path;     ///< JSON path, for error messages

  /// Signed distance (m) of x from the plane, positive on the "+" side.
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
  int region_plane = -1;                 ///< kOnRegionPlane: index into LayoutSpec::region
  LayoutPlane plane;                     ///< kOnPlane: the plane
  Vec3 point = Vec3::Zero();             ///< kNearest: the point (m)
  double max_distance = std::numeric_limits<double>::infinity();  ///< kNearest (m)
  std::string source_path;
};

/// A parsed layout. Exactly one of the two forms: rules (mesh_file empty) or mesh.
struct LayoutSpec {
  std::string source;                    ///< spec file name (or scene file) for errors
  std::string path;                      ///< JSON path of the spec inside `source`
  std::vector<LayoutPlane> region;
  std::vector<LayoutPlane> dividers;
  std::vector<PanelRule> panels;
  std::vector<LayoutOpening> openings;   ///< rules layouts only
  std::string mesh_file;                 ///< OBJ layout (resolved path); empty for rules
  std::vector<PinRule> pins;
  double seam_tolerance = 0.05;          ///< relative seam side length difference
  double plane_tolerance = 1e-4;         ///< m, for "on_plane" with an inline plane
  double weld_tolerance = 1e-6;          ///< m, coincident OBJ vertices are welded

  bool is_mesh_layout() const { return !mesh_file.empty(); }
};

/// Parses a layout spec object. `base_dir` resolves a relative "mesh" path.
/// Throws InputError naming `fields.source()` and the JSON path of the problem.
LayoutSpec parse_layout_spec(JsonFields& fields, const std::string& base_dir);

/// Reads and parses a layout spec JSON file.
LayoutSpec read_layout_spec(const std::string& file);

}  // namespace tightfit
