#pragma once
/// Files written after a simulation: the garment and the deformed body as PLY with
/// per-face and per-vertex fields, and result.json with energies, convergence, timings
/// and pressure statistics.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/report/fit_view.hpp"
#include "tightfit/report/html.hpp"
#include "tightfit/report/pressure_statistics.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

/// Garments with more pieces than this (covers: one piece per triangle) get no per-piece
/// and per-seam statistics: there is nothing to cut or sew.
constexpr size_t kMaxReportedPieces = 64;

/// Per-face fields of the garment (one row per garment triangle):
/// stretch_max, stretch_min (principal stretches, 1.3 = 30 %), stretch_dir (3D unit
/// direction of the maximum stretch), regime (0 slack, 1 wrinkled, 2 taut),
/// tension_max (N/m), pressure_pa and pressure_mmhg (Eq. 31 with the chosen shape
/// operator), pressure_mid_edge_pa, pressure_limit_pa, piece (piece index).
std::vector<MeshField> garment_face_fields(const GarmentSimulation& sim, const FitAnalysis& fit,
                                           ShapeOperatorKind pressure_operator);
/// Per-vertex fields of the garment: normal_force (N), force (3, N) on the body,
/// vertex_pressure_pa (force over Voronoi area, for comparison).
std::vector<MeshField> garment_vertex_fields(const FitAnalysis& fit);

/// Pressure per element with the chosen operator (Pa).
const VecX& chosen_pressure(const FitAnalysis& fit, ShapeOperatorKind op);

/// Statistics of the fit: pressure min/median/max (Pa and mmHg, overall and per piece;
/// medians area-weighted like the report's, fit_stats.hpp),
/// the area-weighted mean, standard deviation and spread (std / mean) of the pressure,
/// area shares of slack / wrinkled / taut elements, lift-off area (negative pressure),
/// stretch ranges, and per pressure region (pressure_statistics.hpp) its statistics
/// against the target and the compression class reached ("pressure_regions", only
/// when `regions` is not empty; resolve_fit_regions gives them), and with "pieces" per
/// seam its lengths, mismatch, sewing stretch, traction and angle to the body's unit up
/// direction `up` ("seams", seam_statistics.hpp).
nlohmann::json fit_statistics(const GarmentSimulation& sim, const FitAnalysis& fit,
                              ShapeOperatorKind pressure_operator,
                              const std::vector<FitRegion>& regions = {},
                              const Vec3& up = Vec3::UnitY());

/// JSON of a Newton report (iterations, residuals, time split).
nlohmann::json newton_report_json(const NewtonReport& report);

/// The limit-surface positions of the body's surface vertices (ns×3, m) for body
/// positions `y` (n_b×3): what the report draws, so that the garment lying on the limit
/// surface is not pierced by the control mesh.
Points3 body_limit_positions(const Body& body, const LimitSurface& surface, const Points3& y);

/// The fit as the report and glTF writers see it: deformed body, garment with the
/// standard face fields (fit_view.hpp), the pattern, the scene parameters and an
/// optimization history (may be an empty array); seam angles against the body's unit up
/// direction `up`.
FitView make_fit_view(const GarmentSimulation& sim, const FitAnalysis& fit,
                      ShapeOperatorKind pressure_operator, const nlohmann::json& parameters,
                      const nlohmann::json& history = nlohmann::json::array(),
                      const Vec3& up = Vec3::UnitY());

/// The report's colourings of a fit: the standard ones (fit_colormap.hpp), then sliding
/// (fits with poses) and the distance to the shape target (fits with a shape objective)
/// when the view has those fields.
std::vector<FieldColoring> fit_report_colorings(const FitView& view);

/// Writes fit.glb (garment coloured by max stretch, with the body) and report.html
/// (three.js viewer, colour maps, pieces, statistics) into `folder`; `title` heads the
/// report (ReportOptions::title).
void write_fit_report(const std::filesystem::path& folder, const FitView& view,
                      const std::string& title = ReportOptions{}.title);

/// Writes garment.ply, body.ply (deformed surface; per-vertex displacement in m) into
/// `folder` (atomic per file).
void write_fit_meshes(const std::filesystem::path& folder, const GarmentSimulation& sim,
                      const FitAnalysis& fit, ShapeOperatorKind pressure_operator);

}  // namespace tightfit
