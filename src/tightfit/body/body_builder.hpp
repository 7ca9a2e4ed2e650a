#pragma once
/// Building a Body from a closed surface: tetrahedralization that keeps the surface
/// (tetrahedralize.hpp) and the pinned core (pinned_core.hpp); and the built-in
/// generator bodies.
#include <string>
#include <utility>
#include <vector>

#include "tightfit/body/body.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/body/loop_limit.hpp"
#include "tightfit/body/pinned_core.hpp"
#include "tightfit/body/tetrahedralize.hpp"

namespace tightfit {

/// How the volume of a body is meshed and pinned.
struct VolumeOptions {
  TetQuality quality;
  CoreOptions core;
};

/// Defaults for a surface with edges of about `edge_length` (m): radius-edge ≤ 1.4,
/// min dihedral 12° (TetGen target), tets no larger than a regular tet of edge
/// 2·edge_length (the interior may be coarser than the surface), core = vertices deeper
/// than 15 mm, bone samples every edge_length at least edge_length/2 from the surface.
VolumeOptions default_volume_options(double edge_length);

/// What happened while building a body: sizes before processing, stage timings and
/// intermediate results. Filled by the builders when passed.
struct BuildReport {
  /// Wall-clock seconds per stage, in the order the stages ran.
  std::vector<std::pair<std::string, double>> stage_seconds;
  int input_vertices = 0;  ///< surface read or generated, before crop/remesh
  int input_faces = 0;
  double input_volume = 0.0;   ///< m³, enclosed by the input surface (after scaling)
  double input_area = 0.0;     ///< m²
  int feature_edges = 0;       ///< constrained edges kept by the remeshing
  int remesh_refinements = 0;  ///< local refinement rounds against self-intersections
  bool limit_fitted = false;   ///< whether control points were fitted to the limit surface
  LimitFitResult limit_fit;
  int bone_points = 0;  ///< bone samples inserted as volume vertices
  std::string tetgen_switches;
  /// What the import did to the input that the user should know (parts left out, units
  /// guessed), one sentence each naming the file.
  std::vector<std::string> warnings;

  void add_stage(const std::string& name, double seconds) {
    stage_seconds.emplace_back(name, seconds);
  }
  double total_seconds() const;
};

/// Tetrahedralizes the closed, outward-oriented surface (Body invariant: surface vertex
/// i == volume vertex i) and pins its core. Appends the stages "tetrahedralize" and
/// "core" to `report`. Throws InputError (source "surface" or the core's source) on
/// unusable input, SolverError if TetGen fails otherwise.
Body body_from_surface(const TriMesh& surface, const VolumeOptions& options,
                       BuildReport* report = nullptr);

/// The surface of the generated body of `params` (stage "generate" in `report`), before
/// its volume is meshed: cylinder_body(params, options) is body_from_surface of it.
TriMesh generated_surface(const CylinderParams& params, BuildReport* report = nullptr);
TriMesh generated_surface(const SphereParams& params, BuildReport* report = nullptr);

/// The capped cylinder of `params` as a Body, meshed with `options`
/// (default_volume_options of its edge length when omitted).
Body cylinder_body(const CylinderParams& params, BuildReport* report = nullptr);
Body cylinder_body(const CylinderParams& params, const VolumeOptions& options,
                   BuildReport* report = nullptr);
/// The sphere of `params` as a Body.
Body sphere_body(const SphereParams& params, BuildReport* report = nullptr);
Body sphere_body(const SphereParams& params, const VolumeOptions& options,
                 BuildReport* report = nullptr);

}  // namespace tightfit
