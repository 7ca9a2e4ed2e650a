#pragma once
/// Built-in analytic bodies in metres: a capped cylinder and a sphere, as closed,
/// outward-oriented triangle meshes with well-shaped triangles, and their analytic
/// surfaces (closest-point projection, volume, area) for tests against exact values.
///
/// Limit fitting (default on): the garment lives on the Loop limit surface of the
/// control mesh, which shrinks relative to it. With `fit_limit` the control points are
/// moved (loop_limit.hpp, `fit_loop_limit`) until the limit position of every vertex lies
/// on the analytic surface; the control points then lie slightly outside it (about
/// R·α²/8 for a cylinder with angular vertex spacing α), and the tet volume (= volume of
/// the control polyhedron) exceeds the analytic volume by about α²/12 (cylinder side).
#include "tightfit/body/loop_limit.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// End caps of the cylinder.
enum class CapStyle {
  /// Hemispheres of the cylinder's radius (a capsule): the surface is smooth (C1), so
  /// the Loop limit surface can follow it everywhere. The default.
  kRound,
  /// Flat discs. The rim is a 90° crease that the (crease-free) Loop limit surface
  /// rounds off over about one edge length; the limit fit still puts every vertex's
  /// limit point on the closed cylinder.
  kFlat,
};

/// A capped cylinder. The cylindrical side has length `length` between the two rims,
/// centred at `center` along the unit `axis`. Round caps add a hemisphere of radius
/// `radius` at each end (total length `length + 2 radius`); flat caps close the rims.
struct CylinderParams {
  double radius = 0.05;      ///< m, > 0
  double length = 0.3;       ///< m, ≥ 0 (side length without the caps)
  double edge_length = 0.0;  ///< target edge length (m); 0 → `2π radius / 48`
  CapStyle caps = CapStyle::kRound;
  Vec3 center = Vec3::Zero();  ///< m
  Vec3 axis = Vec3::UnitZ();   ///< direction of the axis (normalized on use)
  bool fit_limit = true;       ///< fit the Loop limit surface to the analytic surface
};

/// A sphere of radius `radius` around `center`.
struct SphereParams {
  double radius = 0.1;         ///< m, > 0
  double edge_length = 0.0;    ///< target edge length (m); 0 → `2π radius / 48`
  Vec3 center = Vec3::Zero();  ///< m
  bool fit_limit = true;       ///< fit the Loop limit surface to the analytic surface
};

/// Edge length used when `edge_length` is 0: 48 edges around a great circle, which puts
/// the tet volume within 1 % of the analytic volume (with or without limit fitting).
double default_generator_edge_length(double radius);

/// Triangulated capped cylinder: rings of ⌈2πR/h⌉ vertices, consecutive side rings
/// rotated by half a step so that side triangles are near-equilateral and every side
/// vertex has valence 6; caps are rings of shrinking vertex count (latitude rings on the
/// hemisphere, concentric rings on a flat disc) closed by a pole vertex. Throws
/// std::invalid_argument on non-positive radius or edge length, negative length.
/// `fit` (optional) receives the limit-fit result when `fit_limit` is set.
TriMesh cylinder_surface(const CylinderParams& params, LimitFitResult* fit = nullptr);

/// Geodesic sphere: an icosahedron whose faces are split into k² triangles
/// (k = ⌈edge of the icosahedron / h⌉) and projected onto the sphere; 12 vertices of
/// valence 5, all others valence 6.
TriMesh sphere_surface(const SphereParams& params, LimitFitResult* fit = nullptr);

/// The concentric core of a generator body with the uniform soft-tissue thickness
/// `radius − core_radius` (0 < core_radius < radius): a capsule of the same length for
/// round caps, a cylinder shortened by twice the thickness for flat caps (which must
/// leave a positive length), a concentric sphere. Not limit-fitted (it is not a garment
/// surface); edge length min(h, 2π core_radius / 32) (volume within 1 %). Use it as
/// CoreOptions::embedded_core (an exact bone for the Lamé check of docs/design.md §7).
/// Throws std::invalid_argument for a core radius out of range.
CylinderParams cylinder_core(const CylinderParams& body, double core_radius);
SphereParams sphere_core(const SphereParams& body, double core_radius);

/// Closest point of the analytic capped cylinder's surface to `p` (m).
Vec3 project_to_cylinder(const CylinderParams& params, const Vec3& p);
/// Closest point of the analytic sphere to `p` (m); the centre maps to an arbitrary pole.
Vec3 project_to_sphere(const SphereParams& params, const Vec3& p);

/// Analytic area (m²) of the capped cylinder (round or flat caps), for mesh budgets.
double cylinder_area(const CylinderParams& params);
/// Analytic area (m²) of the sphere, for mesh budgets.
double sphere_area(const SphereParams& params);

}  // namespace tightfit
