#pragma once
/// The saved state of a run (`state.json`), written by `tightfit simulate`, `layout` and
/// `optimize` into their output folder and read by `tightfit export`, which regenerates
/// every output file from it without solving again.
///
/// state.json: {"format": "tightfit-run-state", "version": 1,
///   "command": "simulate" | "layout" | "optimize",
///   "scene_file": the scene file as given, "scene_base_dir": absolute folder that the
///   scene's relative paths (body mesh, layout mesh, shape target) resolve against,
///   "scene": the scene document,
///   "pattern": {"pieces": [{"name", "rest": [[x, y], ...] (m), "triangles": [[a, b, c], ...]}]}
///     when the garment is the scene's (rest positions aside), or, when the run remeshed
///     pieces, {"remeshed": true, the complete pattern (scene/pattern_record.hpp):
///     "pieces" with boundaries, corners and grain, "seams", "pinned"},
///   "garment": [[face, u, v], ...] (one per garment vertex: its limit-surface point),
///   "body": [[x, y, z], ...] (m, deformed body vertices),
///   "history": {"terms": [names], "iterations": [records]} (optimize only; the records
///     of history.json, scene/optimization_checkpoint.hpp),
///   "result": the command's summary (result.json, or layout.json for layout)}
/// Doubles are written in nlohmann::json's round-trip form (shortest digits that parse
/// back to the same double), so a read state is bit-identical to the written one.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <optional>
#include "tightfit/body/body.hpp"
#include "tightfit/design/optimization_state.hpp"

#include "tightfit/garment/garment.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"

namespace tightfit {

/// One pattern piece as saved: its rest positions and its mesh (to check that the scene
/// still builds the same garment).
struct RunStatePiece {
  std::string name;
  Points2 rest;         ///< n×2 rest positions (m), as after optimization
  Triangles triangles;  ///< piece-local vertex indices
};

struct RunState {
  std::string command;                   ///< "simulate", "layout" or "optimize"
  std::string scene_file;                ///< the scene file the run read (for reports)
  std::filesystem::path scene_base_dir;  ///< absolute; relative scene paths resolve here
  nlohmann::json scene;                  ///< the scene document
  std::vector<RunStatePiece> pieces;     ///< the pattern, piece by piece
  /// The complete pattern (rest positions as in `pieces`) when it differs from the
  /// scene's (pieces remeshed during optimization): export welds the garment from it.
  std::optional<Pattern> pattern;
  EmbeddedState state;                  ///< garment embedding (n_g) and body positions (n_b×3, m)
  std::vector<std::string> term_names;  ///< optimize: names of the objective terms
  std::vector<OptimizationIteration> history;  ///< optimize: accepted iterations; else empty
  nlohmann::json result;                       ///< the command's summary (an object)
  /// optimize: the garment at the initial equilibrium (m), for the report's shape
  /// silhouettes; absent when unknown (a resumed run).
  std::optional<TriMesh> initial_garment;
};

/// The run state of `command` for the scene `spec`, with the garment's pattern (rest
/// positions as they are in `garment`) and the simulation state `state`. When
/// `scene_pattern` (the pattern the scene builds) is given and its meshes differ from
/// the garment's (same_pattern_meshes), the complete pattern is saved too. History and
/// result are left empty for the caller.
RunState make_run_state(const std::string& command, const SceneSpec& spec, const Garment& garment,
                        const EmbeddedState& state, const Pattern* scene_pattern = nullptr);

/// The history.json document: {"terms": names, "iterations": [iteration records]}.
nlohmann::json history_json(const std::vector<OptimizationIteration>& history,
                            const std::vector<std::string>& term_names);

nlohmann::json run_state_json(const RunState& state);
/// Reads a state document; InputError names `source` and the JSON path of the first
/// problem (unknown format or version, a missing or mistyped field).
RunState run_state_from_json(const nlohmann::json& j, const std::string& source);

/// Writes `file` atomically.
void write_run_state(const std::filesystem::path& file, const RunState& state);
/// Reads `file` (InputError naming it when it is missing, not JSON, or malformed).
RunState read_run_state(const std::filesystem::path& file);

/// The scene of a state, parsed again (relative paths against scene_base_dir).
/// InputError names `source` when the document is no longer a valid scene.
SceneSpec run_state_scene(const RunState& state, const std::string& source);

/// The run's garment, checked against the garment and body rebuilt from its scene:
///  * without a saved complete pattern: the scene's garment `scene_garment` with the
///    saved rest positions; the saved pieces must match the scene's (names, vertex
///    counts, triangles);
///  * with one (a remeshed run): weld_pattern of the saved pattern; its pieces, seams
///    and pinned boundaries must correspond to the scene's (counts, names, and the
///    pieces that seams and pinned boundaries join);
/// and in both cases one surface point per garment vertex on an existing face and one
/// position per body vertex. The embedding is the saved one. InputError names `source`
/// and the JSON path of the first mismatch.
Garment run_state_garment(const RunState& state, const Garment& scene_garment, const Body& body,
                          int num_surface_faces, const std::string& source);

/// The saved rest positions stacked over all pieces (num_pattern_vertices × 2, m), for
/// Garment::set_rest_positions / GarmentSimulation::set_rest_positions.
Points2 stacked_rest_positions(const RunState& state);

}  // namespace tightfit
