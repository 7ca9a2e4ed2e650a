#pragma once
/// The simulated fit as the exports see it: plain arrays that the simulation fills and
/// that the glTF and report writers read (fit_glb.hpp, report_html.hpp).
///
/// Units: positions in metres, pressures in Pa (mmHg only as a derived field, 1 mmHg =
/// kPascalPerMmHg Pa), forces in N, stretches dimensionless (1.3 = 30 % stretch).
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/ease_table.hpp"
#include "tightfit/garment/pattern.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/report/seam_statistics.hpp"

namespace tightfit {

/// Names of the standard garment face fields. The writers accept any field; these are
/// the ones the report's colour maps and statistics look for.
namespace fit_fields {
/// Largest principal stretch s1 of the face (dimensionless, 1 = rest length).
inline constexpr std::string_view kStretchMax = "stretch_max";
/// Smallest principal stretch s2 <= s1 (dimensionless).
inline constexpr std::string_view kStretchMin = "stretch_min";
/// Unit 3D direction of s1 in the deformed face (3 components).
inline constexpr std::string_view kStretchDirection = "stretch_dir";
/// Cloth regime: 0 slack, 1 wrinkled, 2 taut (ClothRegime's order).
inline constexpr std::string_view kRegime = "regime";
/// Pressure on the body (Pa): positive presses onto the body, negative means the
/// fabric would lift off there (never clamped).
inline constexpr std::string_view kPressurePa = "pressure_pa";
/// The same pressure in mmHg.
inline constexpr std::string_view kPressureMmHg = "pressure_mmhg";
/// Normal force of the face on the body (N): pressure times deformed face area.
inline constexpr std::string_view kNormalForce = "normal_force_n";
/// Tangential force above the friction limit (N), per face the mean of its vertices',
/// in the worst pose of the scene (report/pose_outputs.hpp); only in fits with poses.
inline constexpr std::string_view kSlidingExcess = "sliding_excess_n";
/// Distance to the shape objective's target (mm): per face the mean |distance| of its
/// corners (report/shape_outputs.hpp); only in fits of scenes with a shape objective.
inline constexpr std::string_view kShapeDistance = "shape_distance_mm";
/// The force the state leaves unbalanced (N), per face the mean of its vertices'
/// (EmbeddedEquilibrium::garment_residual_forces); only in fits whose solve did not
/// converge (`simulate --keep-failed`).
inline constexpr std::string_view kResidualForce = "residual_force_n";
}  // namespace fit_fields

/// The fit in one pose of the body (report/pose_outputs.hpp): the garment carried there with
/// its neutral embedding, and the posed body, for the report's pose switch.
struct FitPose {
  std::string name;
  Points3 garment;             ///< garment vertices in the pose (n_g×3, m)
  Points3 garment_normals;     ///< outward unit normals of the posed body there (n_g×3)
  Points3 body;                ///< the body surface's vertices in the pose (FitView::body rows)
  VecX sliding_excess;         ///< per garment face: mean tangential force above the limit (N)
  double sliding_share = 0.0;  ///< share of the free garment vertices that would slide
};

/// A quantity per face of a mesh.
struct FaceField {
  std::string name;  ///< [A-Za-z0-9_]+, unique within its mesh (e.g. "pressure_pa")
  std::string unit;  ///< "Pa", "mmHg", "N", "" for dimensionless, ...
  /// num_faces × components: one row per face, 1 column for a scalar, 3 for a 3D
  /// vector. NaN marks a face without a value (no writer puts one in a file:
  /// common/finite_output.hpp).
  MatX values;

  int components() const { return static_cast<int>(values.cols()); }
};

/// Everything the fit exports show. Garment faces and pattern triangles are the same
/// triangles: `piece_faces` says which garment face each pattern triangle became.
/// A pressure target region on the garment (design/pressure_region.hpp) as the
/// outputs see it: its target range and the garment faces it holds (membership >= ½).
struct FitRegion {
  std::string name;
  double min_pa = 0.0;     ///< Pa
  double max_pa = 0.0;     ///< Pa
  std::vector<int> faces;  ///< garment faces, ascending
};

struct FitView {
  /// The body's up direction in the scene's frame (scene/body_up.hpp); the glb turns it
  /// onto glTF's +y.
  Vec3 up = Vec3::UnitY();
  TriMesh body;                        ///< deformed body surface (m)
  std::vector<FaceField> body_fields;  ///< per body face; may be empty
  TriMesh garment;                     ///< garment in 3D (m), welded across seams
  /// Outward unit normals of the body surface at the garment vertices (n_g×3), which
  /// the report lifts the garment along for display (may be empty).
  Points3 garment_normals;
  /// Garment vertices held on the body (sorted; pinned cuffs and waistbands).
  std::vector<int> pinned_vertices;
  std::vector<FaceField> garment_fields;  ///< per garment face (see fit_fields)
  Pattern pattern;                        ///< 2D pieces (m) and seams
  /// piece_faces[k][t]: the garment face of triangle t of piece k. Empty means the
  /// garment faces are the pieces' triangles in piece order (piece 0 first). Every
  /// garment face belongs to exactly one pattern triangle.
  std::vector<std::vector<int>> piece_faces;
  nlohmann::json parameters = nlohmann::json::object();  ///< scene parameters to show
  /// Optimization history: an array of per-iteration objects, e.g.
  /// {"iteration": 3, "objective": 0.12, "gradient_norm": 1e-3}; may be empty.
  nlohmann::json history = nlohmann::json::array();
  /// Pressure target regions; may be empty.
  std::vector<FitRegion> pressure_regions;
  /// Per piece (empty, or one per pattern piece): the piece's outline before the
  /// optimization (n×2, m, the pattern's frame), drawn dashed under the optimized one.
  /// An empty entry: nothing to compare (e.g. a piece the scene does not have).
  std::vector<Points2> initial_outlines;
  /// The run at a glance, shown at the top of the report (an object; may be empty):
  /// e.g. {"command", "scene", "version", "date", "status", "stop_reason",
  /// "iterations", "seconds", "force_residual_n", "objective_initial",
  /// "objective_final"}.
  nlohmann::json summary = nlohmann::json::object();
  /// The fabric, its curves and working points (report/fabric_outputs.hpp); null: none.
  nlohmann::json fabric = nullptr;
  /// The scene's poses (empty without poses).
  std::vector<FitPose> poses;
  /// Per seam of the pattern (or empty): side lengths, mismatch, sewn length, sewing
  /// stretch and traction (report/seam_statistics.hpp), the report's seam table.
  std::vector<SeamStatistics> seams;
  /// The shape objective's target surface (m; empty without one) and the garment at the
  /// optimization's initial equilibrium (empty when unknown): the report's silhouettes
  /// (initial, optimized, target) in a front and a side view.
  TriMesh shape_target;
  TriMesh initial_garment;
  /// The ease table (garment/ease_table.hpp): body and pattern circumferences and the
  /// ease at the measurement levels; the report's measurements table. May be empty.
  EaseTable measurements;
};

/// Checks shapes and indices: faces index existing vertices, every field has one row
/// per face of its mesh and a valid unique name, the pattern triangles map one-to-one
/// onto the garment faces, `history` is an array and `parameters` and `summary` objects,
/// `initial_outlines` is empty or has one finite n×2 outline (n ≠ 1, 2) per piece.
/// Throws InputError with `source` (e.g. the output file) naming the problem.
void validate_fit_view(const FitView& view, const std::string& source);

/// The field called `name`, or nullptr.
const FaceField* find_field(const std::vector<FaceField>& fields, std::string_view name);

/// piece_faces resolved: the explicit mapping, or the piece-order concatenation when
/// FitView::piece_faces is empty. Assumes a valid view.
std::vector<std::vector<int>> resolved_piece_faces(const FitView& view);

/// A pressure field in mmHg ("pressure_mmhg") from one in Pa.
FaceField pressure_mmhg_field(const FaceField& pressure_pa);

}  // namespace tightfit
