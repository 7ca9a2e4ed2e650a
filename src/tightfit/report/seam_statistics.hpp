#pragma once
/// What a sewer and an engineer want to know about every seam: the
/// sewing lengths of its two sides in the pattern (they must agree to be sewn; their
/// difference is the mismatch), and on a fit the seam's sewn 3D length, the sewing
/// stretch of each side (sewn length / side length) and the normal traction the cloth
/// pulls on it with (paper Eq. 36, seam_traction_objective.hpp) per unit seam length.
///
/// Units: lengths in m, tractions in N/m (force per unit rest length of the seam), the
/// total traction in N; the JSON writers convert lengths to mm.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"

namespace tightfit {

/// One seam's lengths and, on a fit, its sewn length and traction.
struct SeamStatistics {
  std::string name;
  std::string piece_a;          ///< name of the piece of side a
  std::string piece_b;          ///< name of the piece of side b
  double length_a = 0.0;        ///< rest (pattern) length of side a (m)
  double length_b = 0.0;        ///< rest (pattern) length of side b (m)
  bool has_fit = false;         ///< the fit members below are set
  double sewn_length = 0.0;     ///< 3D length of the sewn seam on the fit (m)
  double traction_mean = 0.0;   ///< length-weighted mean normal traction, both sides (N/m)
  double traction_max = 0.0;    ///< largest normal traction of a seam element (N/m)
  double traction_total = 0.0;  ///< Σ l0 · traction over both sides (N): its share of T_seam
  /// Length-weighted mean angle of the sewn seam's edges to the body's up axis
  /// (scene/body_up.hpp: y for a mesh body, a generated cylinder's axis), degrees: 0 for a
  /// seam running up the body, 90 for one around it; a helical seam lies in between.
  double angle_to_up_deg = 0.0;

  /// |length_a − length_b| (m).
  double mismatch() const;
  /// sewn_length / length_a and / length_b (1.2 = the side is stretched 20 % when sewn).
  double stretch_a() const;
  double stretch_b() const;
};

/// The pattern-only statistics (names and side lengths) of every seam, in pattern order.
std::vector<SeamStatistics> pattern_seam_statistics(const Pattern& pattern);

/// The statistics of every seam on a fit: garment positions `x` (n_g×3, m) over the
/// garment's pattern, tractions with the simulated cloth `material`. Every mean and the
/// total are over the seam-adjacent elements of both sides (each seam edge with the
/// triangle that holds it), weighted by the edge's rest length; seam angles against the
/// unit direction `up`.
std::vector<SeamStatistics> fit_seam_statistics(const Garment& garment, const Points3& x,
                                                const ClothMaterial& material,
                                                const Vec3& up = Vec3::UnitY());

/// One seam as JSON: {"name", "piece_a", "piece_b", "length_a_mm", "length_b_mm",
/// "mismatch_mm"} and, on a fit, {"sewn_length_mm", "stretch_a", "stretch_b",
/// "traction_mean_n_per_m", "traction_max_n_per_m", "traction_total_n", "angle_to_up_deg"}.
nlohmann::json seam_statistics_json(const SeamStatistics& seam);

/// All seams as a JSON array (seam_statistics_json each).
nlohmann::json seam_statistics_json(const std::vector<SeamStatistics>& seams);

}  // namespace tightfit
