#include "tightfit/body/pinned_core.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "tightfit/common/error.hpp"

namespace tightfit {

Points3 bone_sample_points(const CoreOptions& options, const SurfaceDistance& surface) {
  std::vector<Vec3> points;
  if (options.bone_sample_spacing > 0.0)
    for (const BoneSegment& bone : options.bones) {
      const double length = (bone.tail - bone.head).norm();
      const int segments =
          std::max(1, static_cast<int>(std::ceil(length / options.bone_sample_spacing)));
      for (int i = 0; i <= segments; ++i) {
        const Vec3 p = bone.head + (bone.tail - bone.head) * (double(i) / segments);
        const bool duplicate = std::any_of(points.begin(), points.end(), [&](const Vec3& q) {
          return (q - p).norm() < 0.5 * options.bone_sample_spacing;
        });
        if (duplicate || surface.distance(p) < options.bone_sample_clearance ||
            !surface.contains(p))
          continue;
        points.push_back(p);
      }
    }
  Points3 out(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = points[i];
  return out;
}

std::vector<int> pinned_core(const TetMesh& volume, int num_surface_vertices,
                             const SurfaceDistance& surface, const CoreOptions& options,
                             int num_always_pinned) {
  if (options.soft_tissue && !(*options.soft_tissue > 0.0))
    throw InputError(options.source, "the soft-tissue thickness must be positive");
  if (!(options.bone_radius >= 0.0))
    throw InputError(options.source, "the bone radius must be non-negative");
  std::vector<int> pinned;
  double deepest = 0.0;
  const std::optional<SurfaceDistance> core =
      options.embedded_core.num_faces() > 0
          ? std::optional<SurfaceDistance>(std::in_place, options.embedded_core)
          : std::nullopt;
  for (int v = num_surface_vertices; v < volume.num_vertices(); ++v) {
    const Vec3 p = volume.vertices.row(v);
    bool pin = v < num_surface_vertices + num_always_pinned || (core && core->contains(p));
    if (options.soft_tissue) {
      const double depth = surface.distance(p);
      deepest = std::max(deepest, depth);
      pin = pin || depth >= *options.soft_tissue;
    }
    for (size_t b = 0; !pin && b < options.bones.size(); ++b)
      pin = distance_to_bone(options.bones[b], p) <= options.bone_radius;
    if (pin) pinned.push_back(v);
  }
  if (pinned.empty()) {
    char buffer[256];
    if (options.soft_tissue)
      std::snprintf(buffer, sizeof buffer,
                    "no vertex is pinned: the deepest interior vertex is %.4g m below the "
                    "surface, the soft-tissue thickness is %.4g m",
                    deepest, *options.soft_tissue);
    else
      std::snprintf(buffer, sizeof buffer,
                    "no vertex is pinned: no interior vertex lies within %.4g m of the bones",
                    options.bone_radius);
    throw InputError(options.source, buffer);
  }
  return pinned;
}

}  // namespace tightfit
