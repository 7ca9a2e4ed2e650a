#pragma once
/// Test garments that need no layout machinery:
/// a sleeve (tube) wrapped around a cylinder and a closed cover of a whole body, both
/// generated directly on the limit surface with their rest shape scaled down.
#include "tightfit/garment/garment.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// A rectangular piece wrapped around a cylinder, its two long edges sewn together by
/// one seam along the axis. The piece's x axis runs around the cylinder, its y axis
/// along it.
struct SleeveParams {
  double radius = 0.05;        ///< m, radius of the cylinder the sleeve is put on
  Vec3 center = Vec3::Zero();  ///< m, a point on the cylinder axis
  Vec3 axis = Vec3::UnitZ();   ///< cylinder axis (normalized on use)
  double axial_begin = -0.1;   ///< m, start of the sleeve along the axis from `center`
  double axial_end = 0.1;      ///< m, end of the sleeve along the axis from `center`
  double hoop_scale = 0.9;     ///< rest circumference / 2πR (< 1 stretches the sleeve)
  double axial_scale = 1.0;    ///< rest length / (axial_end − axial_begin)
  double edge_length = 0.01;   ///< m, target rest edge length
  /// Irregularity: interior vertices are moved by up to this fraction of the grid
  /// spacing, and each grid cell's diagonal is chosen at random (valences 4..8).
  double jitter = 0.3;
  unsigned seed = 1;
  /// Initial placement off the symmetric state, for sliding tests: the sleeve is turned
  /// by `rotation` (rad) about the axis plus `twist` (rad/m) times the axial position.
  double rotation = 0.0;
  double twist = 0.0;
  /// Pin the vertices of the ring at `axial_begin` (and of the ring at `axial_end`) to
  /// the body. A sleeve with free ends on a frictionless body has no axial stiffness in
  /// the wrinkled regime (tension field theory): pinning both rings fixes its length.
  bool pin_first_ring = false;
  bool pin_last_ring = false;
};

/// Builds the sleeve piece (name "sleeve"), its seam ("axial seam") and the embedding
/// of every garment vertex on `surface` (projection of the wrapped position).
/// `control`: the surface's control positions (num_control_vertices × 3, m).
Garment make_sleeve(const SleeveParams& params, const LimitSurface& surface,
                    const Points3& control);

/// A closed cover of the whole limit surface: one garment vertex at the limit point of
/// every control vertex, one garment triangle per control face, and each triangle's
/// rest shape equal to its 3D shape scaled by `scale` (each triangle is its own piece,
/// so the rest state needs no flattening). With scale < 1 every triangle is stretched
/// isotropically by 1/scale.
Garment make_cover(const LimitSurface& surface, const Points3& control, double scale);

}  // namespace tightfit
