#pragma once
/// The JSON description of a body, used stand-alone (`tightfit body SPEC`) and as the
/// "body" section of scene files. Lengths in metres, angles in degrees. One of:
///
///   {"generator": "cylinder", "radius": 0.05,
///    "length": 0.3,                  // of the cylindrical side, without the caps
///    "edge_length": 0.01,            // default 2π radius / 48
///    "caps": "round" | "flat",       // default "round" (hemispheres; see generators.hpp)
///    "center": [0, 0, 0], "axis": [0, 0, 1],
///    "fit_limit": true}              // Loop limit surface through the analytic surface
///   {"generator": "sphere", "radius": 0.1, "edge_length": ..., "center": [...],
///    "fit_limit": true}
///   {"mesh": "data/bodies/mh_legs_male.obj",   // relative to the spec's folder
///    "scale": 1.0,                    // multiplies the file's coordinates (mm → m: 0.001)
///    "crop": [{"point": [0, 0.5, 0], "normal": [0, 1, 0]}],  // keep where the normal points
///    // or anchored on the skeleton (body/skeleton_anchor.hpp), and "local": only the
///    // part beyond the cut loop nearest the point goes (a hand, not the leg behind):
///    //  {"point": {"bone": "hand.L", "at": 0}, "normal": "-along_bone", "local": true}
///    "skeleton": "data/rig/mh_male_regular.joints.json",  // for anchored crops; in a
///                                     // scene the "rig"'s joints are the default
///    "edge_length": 0.015,            // remeshing target; default 0.015
///    "remesh": true, "remesh_iterations": 5,
///    "sharp_angle_deg": 60,           // closed crease loops (cap rims) kept while remeshing
///    "fit_limit": false}              // fit the limit surface to the (cropped) input
///
/// plus, for all kinds, the volume mesh and core:
///
///   "max_radius_edge": 1.4,           // TetGen radius-edge bound (≥ 1)
///   "min_dihedral_deg": 12,           // TetGen dihedral target (0..18)
///   "interior_edge_length": 0.03,     // tets ≤ a regular tet of this edge; default 2·edge_length
///   "core": {"soft_tissue": 0.015}    // pin vertices deeper than this (the default
///                                     // when neither bones nor radius are given)
///   "core": {"radius": 0.03}          // generators only: an exact concentric core
///                                     // (capsule/sphere) built into the tet mesh and
///                                     // pinned with everything inside (generators.hpp)
///   "core": {"skeleton": "data/rig/mh_male_regular.joints.json",
///            "bones": ["upperleg02.L", "lowerleg01.L"], "bone_radius": 0.01,
///            "soft_tissue": 0.02}     // optional with bones: the union is pinned
///
/// Unknown keys, wrong types and out-of-range values are InputErrors naming the file and
/// the JSON path (common/json_fields.hpp).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tightfit/body/body.hpp"
#include "tightfit/body/body_builder.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/surface_remeshing.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit {

enum class BodySource { kCylinder, kSphere, kMesh };

/// A skeleton by bone name (body/skeleton.hpp) and the file it came from, for messages.
struct SkeletonRef {
  const std::map<std::string, BoneSegment>* bones = nullptr;
  std::string source;
};

/// A body imported from a surface mesh file.
struct MeshImport {
  std::filesystem::path path;  ///< resolved against the spec's base folder
  double scale = 1.0;          ///< applied to the file's coordinates
  /// Metres per file unit ("units": "m" / "cm" / "mm"); 0: guessed from the body's size
  /// (scan_import.hpp) unless "scale" is given.
  double units = 0.0;
  bool scale_given = false;  ///< "scale" was in the spec: no guessing
  std::vector<CropPlane> crop;
  bool remesh = true;
  RemeshOptions remesh_options;  ///< edge_length is the spec's edge length
  bool fit_limit = false;
};

/// A parsed body spec; `build_body` turns it into a Body.
struct BodySpec {
  BodySource source = BodySource::kCylinder;
  CylinderParams cylinder;   ///< when source == Cylinder
  SphereParams sphere;       ///< when source == Sphere
  MeshImport mesh;           ///< when source == Mesh
  double edge_length = 0.0;  ///< resolved surface edge length (m)
  VolumeOptions volume;
  std::string source_file;  ///< file named in error messages
  std::string json_path;    ///< JSON pointer of the spec in that file ("" = root)
};

/// Parses `j` (an object). `json_path` is its JSON pointer in the document (e.g. "" for
/// a spec file, "/body" in a scene), `base_dir` the folder relative paths are resolved
/// against, `source_file` the file named in errors. A skeleton file named in "core" is
/// read here so that unknown bone names are reported with their JSON path.
/// `rig` is the skeleton that crops anchored on bones are placed on when the body names
/// no "skeleton" of its own (a scene passes its "rig"'s joints).
BodySpec parse_body_spec(const nlohmann::json& j, const std::string& json_path,
                         const std::filesystem::path& base_dir, const std::string& source_file = "",
                         const SkeletonRef& rig = {});
/// Same, reading from an object reader of a larger document (calls `fields.finish()`).
BodySpec parse_body_spec(JsonFields& fields, const std::filesystem::path& base_dir,
                         const SkeletonRef& rig = {});

/// Builds the body: generate, or read + scale + validate + crop + remesh (+ limit fit);
/// then tetrahedralize and pin the core. Stages and timings go to `report`. Errors from
/// the input are InputErrors naming the spec file and JSON path (or the mesh file).
Body build_body(const BodySpec& spec, BuildReport* report = nullptr);

/// The first half of build_body: the body's surface alone (generated, or read + scaled +
/// validated + cropped + remeshed + limit-fitted), its stages and import warnings in
/// `report`. What the garment is built on; the volume does not change it.
TriMesh build_body_surface(const BodySpec& spec, BuildReport* report = nullptr);
/// The second half of build_body: tetrahedralizes `surface` (build_body_surface of the
/// same spec) and pins its core (stages "tetrahedralize" and "core" in `report`). Touches
/// nothing but its arguments, so it may run on a thread of its own.
Body build_body_volume(const BodySpec& spec, const TriMesh& surface, BuildReport* report = nullptr);

}  // namespace tightfit
