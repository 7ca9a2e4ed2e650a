#pragma once
/// Flattening of a disc-shaped surface patch into the plane with low distortion.
///
/// Method: least-squares conformal maps (LSCM, Lévy et al. 2002) with free boundary and
/// two pinned boundary vertices (the two farthest apart, at their 3D distance) give a
/// fold-free, orientation-preserving start that is conformal but may shrink or grow
/// areas; then as-rigid-as-possible local/global iterations (ARAP, Liu et al. 2008)
/// pull every triangle toward an isometry, which makes developable patches exact and
/// balances area and angle distortion on curved ones. Both solves use the cotangent
/// Laplacian through SparseCholesky (ARAP factors once and only back-substitutes per
/// iteration). ARAP rather than angle-based flattening (ABF++, used by the paper)
/// because its energy directly measures the stretch the fabric would feel, it keeps
/// the boundary free, and it needs no nonlinear solver beyond 2×2 SVDs.
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// How far a flattening is from an isometry. Per triangle, J is the 2×2 Jacobian of
/// the map from the 3D triangle (in its own plane) to 2D with singular values σ1 ≥ σ2.
struct DistortionReport {
  double area_3d = 0.0;               ///< m²
  double area_2d = 0.0;               ///< m²
  double area_error = 0.0;            ///< |area_2d − area_3d| / area_3d
  double mean_area_distortion = 0.0;  ///< area-weighted mean of |σ1 σ2 − 1|
  double max_area_distortion = 0.0;   ///< max over triangles of |σ1 σ2 − 1|
  double mean_angle_error_deg =
      0.0;  ///< area-weighted mean of the triangles' mean |θ2D − θ3D| (degrees)
  double max_angle_error_deg = 0.0;  ///< max over all triangle corners of |θ2D − θ3D| (degrees)
  double mean_stretch = 0.0;         ///< area-weighted mean of max(σ1, 1/σ2) − 1
  int flipped = 0;                   ///< triangles with non-positive 2D area
};

/// Distortion of the map mesh.vertices → uv (n×2, m) over mesh.faces.
DistortionReport measure_distortion(const TriMesh& mesh, const Points2& uv);

struct FlattenOptions {
  int max_iterations = 200;  ///< ARAP iterations at most (0: LSCM only)
  double tolerance = 1e-10;  ///< stop when the ARAP energy decreases by less (relative)
  /// Weight w of the boundary-length term w Σ_e (|u_i − u_j| − ℓ_e)² added to the ARAP
  /// energy (ℓ_e: 3D length of boundary edge e), relative to the cotangent weights of
  /// the interior edges (½ cot, ≈ 0.3 for equilateral triangles). It keeps seam sides at
  /// their 3D length on curved panels, where plain ARAP lengthens or shortens the
  /// boundary to spare the interior; it changes nothing on developable panels.
  double boundary_weight = 10.0;
};

struct Flattening {
  Points2 uv;  ///< n×2 flat positions (m); counter-clockwise triangles
  DistortionReport report;
  int iterations = 0;  ///< ARAP iterations done
};

/// Flattens a disc with holes (openings): `loops[0]` is the outer boundary loop, the
/// others the holes' loops, each with the interior on its left as seen from the front
/// of the faces. The LSCM area term and the ARAP boundary-length term run over every
/// loop; a disc without holes is `flatten_panel(mesh, {boundary})`. Throws SolverError
/// if a linear solve fails (degenerate mesh). The result is not checked for overlaps:
/// see find_overlap.
Flattening flatten_panel(const TriMesh& mesh, const std::vector<std::vector<int>>& loops,
                         const FlattenOptions& options = {});

/// Why a flattened disc overlaps itself, or an empty string if it does not: a
/// triangle with non-positive area, or two boundary edges that cross.
std::string find_overlap(const TriMesh& mesh, const std::vector<int>& boundary, const Points2& uv);

/// The same for a panel with holes (loops as in flatten_panel): also two edges of
/// different loops that cross, and a hole that lies outside the outer loop.
std::string find_overlap(const TriMesh& mesh, const std::vector<std::vector<int>>& loops,
                         const Points2& uv);

}  // namespace tightfit
