#pragma once
/// Summary numbers of a built body (for body.json, tests and benchmarks) and the
/// per-element fields written with the volume mesh.
#include <nlohmann/json.hpp>

#include "tightfit/body/body.hpp"
#include "tightfit/body/body_builder.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit {

struct BodyStats {
  int surface_vertices = 0;
  int surface_faces = 0;
  int volume_vertices = 0;
  int tets = 0;
  int pinned = 0;
  double surface_area = 0.0;    ///< m²
  double surface_volume = 0.0;  ///< m³, enclosed by the surface
  double tet_volume = 0.0;      ///< m³, sum of signed tet volumes
  int inverted_tets = 0;        ///< tets with volume ≤ 0
  double min_tet_volume = 0.0;  ///< m³
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double min_radius_edge = 0.0;  ///< circumradius / shortest edge (regular tet: 0.612)
  double mean_radius_edge = 0.0;
  double p99_radius_edge = 0.0;  ///< 99th percentile
  double max_radius_edge = 0.0;
  double mean_surface_edge = 0.0;  ///< m
};

BodyStats compute_body_stats(const Body& body);

/// Per-tet fields "volume" (m³) and "min_dihedral" (degrees).
std::vector<MeshField> body_cell_fields(const Body& body);
/// Per-vertex fields "pinned" (1/0) and "surface" (1 for surface vertices).
std::vector<MeshField> body_point_fields(const Body& body);

/// The body.json document: counts, measures, quality, and the build report's stages
/// and timings. Units are stated in the document ("units" member).
nlohmann::json body_summary_json(const BodyStats& stats, const BuildReport& report);

}  // namespace tightfit
