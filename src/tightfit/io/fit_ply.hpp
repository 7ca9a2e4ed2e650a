#pragma once
/// PLY export of the fit: garment and deformed body with their per-face fields, via
/// the geometry layer's PLY writer (positions as double).
///
/// ASCII by default, with numbers in shortest round-trip form (exact read-back):
/// meshio 5.0 (Debian bookworm's python3-meshio) reads per-face properties of ASCII
/// PLY correctly but misreads them in binary PLY (it takes one value per property).
///
/// Each 1-component field becomes the face property NAME (double); a k-component field
/// becomes NAME_0 .. NAME_{k-1} (e.g. stretch_dir_0..2). Units are those of the field
/// (see fit_fields: pressure_pa in Pa, pressure_mmhg in mmHg, normal_force_n in N,
/// stretches dimensionless, regime 0 slack / 1 wrinkled / 2 taut). Positions in metres.
#include <filesystem>

#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/io/fit_view.hpp"

namespace tightfit {

/// Writes `mesh` with `fields` (one row per face) as PLY, atomically.
/// InputError naming `path` for invalid fields.
void write_face_field_ply(const std::filesystem::path& path, const TriMesh& mesh,
                          const std::vector<FaceField>& fields,
                          PlyEncoding encoding = PlyEncoding::ascii);

/// Writes the garment with garment_fields to `garment_path` and the body with
/// body_fields to `body_path`, after validate_fit_view.
void write_fit_ply(const FitView& view, const std::filesystem::path& garment_path,
                   const std::filesystem::path& body_path,
                   PlyEncoding encoding = PlyEncoding::ascii);

}  // namespace tightfit
