#pragma once
/// The table pattern makers work from: at the standard levels a garment covers (calf,
/// knee, thigh, …), the body's circumference, the pattern's width there and the
/// negative ease, the share by which the pattern is cut smaller than the body
/// (ease % = (pattern − body) / body × 100; negative for a skintight knit).
///
/// A level is a plane (point + unit normal). At each level:
/// * body circumference: the length of the loop along which the plane cuts the body
///   surface around the level's point (geometry/plane_loops.hpp; the point must lie
///   inside the body's cross-section: on a bone, on a limb's axis), on the surface given: the
///   callers pass the body's Loop limit surface at rest evaluated at the control vertices (the
///   triangulated limit surface the garment lies on, before the garment compresses it:
///   what a tape measure gives on the bare body);
/// * garment circumference: the length of the loop around the same point along which
///   the plane cuts the fitted (deformed) garment mesh;
/// * pattern circumference: the same cut mapped into the flat pattern: every segment of
///   the garment's loop lies in one triangle; its two ends, mapped by their barycentric
///   coordinates into the triangle's rest (pattern) positions, give its length in the
///   pattern; the sum over the loop is the pattern's width where it wraps that level,
///   across all pieces and seams (split per piece as well: what a pattern maker measures
///   on each piece).
///
/// Levels the garment does not go all the way around (its loop there is open: the
/// garment's edge or an opening crosses the level) are kept as skipped with the reason;
/// so are levels where the plane misses the body, where no loop of the body's cut goes
/// around the level's point, or where the garment does not reach the level (its cut in
/// the plane comes no nearer the point than 1.1 times the body loop's farthest point).
/// Lengths in m.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// A measurement level: a named plane through `point` with unit normal `normal` (m).
struct MeasurementLevel {
  std::string name;
  std::string origin;  ///< where it came from: "scene", "skeleton" or "planes"
  std::string anchor;  ///< how it was placed, for the reader: "lowerleg01.L at 0.45", "y 0.35 m"
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
};

/// One piece's share of the pattern circumference at a level.
struct PieceWidth {
  std::string piece;
  double width = 0.0;  ///< m, in the flat pattern
};

/// The measurements at one level.
struct LevelMeasurement {
  MeasurementLevel level;
  /// Empty when measured; else why the level has no numbers (then all lengths are 0).
  std::string skipped;
  /// The garment's cut comes to this level's body loop (measured, or skipped because it
  /// goes only part of the way around); false when the plane misses the body, no body
  /// loop goes around the point, or the garment ends before the level.
  bool reached = false;
  double body_circumference = 0.0;     ///< m
  double pattern_circumference = 0.0;  ///< m, summed over the pieces
  double garment_circumference = 0.0;  ///< m, the fitted garment in 3D
  std::vector<PieceWidth> pieces;      ///< pieces with a share, in piece order

  /// (pattern − body) / body × 100 (%; negative: the pattern is smaller than the body).
  double ease_percent() const;
  /// garment / pattern: how far the fitted garment is stretched around the level (1.2 = 20 %).
  double fitted_stretch() const;
};

/// The measurements at all levels, in the order of the levels.
struct EaseTable {
  std::vector<LevelMeasurement> levels;
};

/// The circumference (m) of `body` (a closed surface, m) at `level`: the length of the
/// loop of the plane's cut around the level's point (else the nearest loop); nullopt when
/// the plane misses the body.
std::optional<double> body_circumference(const TriMesh& body, const MeasurementLevel& level);

/// Measures `levels` on `body` (closed surface, m) and the garment: `garment`'s welded
/// triangles at the fitted positions `garment_positions` (num_garment_vertices × 3, m),
/// its pattern's rest positions for the pattern widths.
EaseTable measure_ease(const std::vector<MeasurementLevel>& levels, const TriMesh& body,
                       const Garment& garment, const Points3& garment_positions);

/// For levels the user did not list: drops those that are not `reached` (keeps the
/// measured ones and those the garment covers only part of the way around).
EaseTable drop_uncovered(EaseTable table);

/// Per piece name, one short label line per measured level it has a share of:
/// "calf.L 34.1 cm, piece 13.9 cm, ease -18 %" (the body circumference and the piece's
/// width there in cm with one decimal, the ease of the whole level in whole %), in the
/// table's order. Pieces without a share get no entry.
std::map<std::string, std::vector<std::string>> ease_label_lines(const EaseTable& table);

}  // namespace tightfit
