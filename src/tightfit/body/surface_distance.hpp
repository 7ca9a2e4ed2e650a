#pragma once
/// Distance queries to a closed triangle surface: unsigned distance and closest point
/// through an AABB tree (CGAL), inside test through the generalized winding number.
#include <memory>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

class SurfaceDistance {
 public:
  /// Builds the tree over the faces of `surface` (copied; the mesh need not outlive this).
  explicit SurfaceDistance(const TriMesh& surface);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  /// Exact Euclidean distance (m) from `p` to the nearest point of the surface.
  double distance(const Vec3& p) const;
  /// The nearest point of the surface to `p` (m).
  Vec3 closest_point(const Vec3& p) const;
  /// The face (row of the surface's faces) holding the nearest point to `p`; that point
  /// is stored in `*point` when `point` is not null.
  int closest_face(const Vec3& p, Vec3* point = nullptr) const;
  /// Generalized winding number of the surface around `p` (sum of signed solid angles
  /// over 4π): ≈ 1 inside an outward-oriented closed surface, ≈ 0 outside. O(faces).
  double winding_number(const Vec3& p) const;
  /// True when `winding_number(p) > 0.5`.
  bool contains(const Vec3& p) const { return winding_number(p) > 0.5; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tightfit
