#pragma once
/// JSON forms of the optimization records (optimization_state.hpp): the history file
/// and the checkpoint written during `tightfit optimize` and read by `--resume`.
///
/// checkpoint.json: {"format": "tightfit-optimization-checkpoint", "version": 1,
///   "iteration": k, "parameters": [p...] (m),
///   "state": {"garment": [[face, u, v], ...], "body": [[x, y, z], ...] (m)},
///   "memory": {"s": [[...], ...], "y": [[...], ...]}, "history": [iteration records],
///   "held_ordering" (optional): {"permutation": [n indices], "factor_nonzeros"}, the
///     fill-reducing ordering the held factorization of the accepted point was
///     analysed with (adjoint_gradient.hpp), so that a resumed run factorizes alike,
///   "held_point" (optional): {"parameters": [p...], "state": {...}, "shift": δ}, where
///     that factorization was made (DesignProblem::accepted_held_point): Newton's matrix
///     at that state and those parameters' rest positions, shifted by δ,
///   "remeshed" (only after a remeshing): {"pattern": the complete pattern with the
///     reference rest positions (scene/pattern_record.hpp), "mesh_rest": per piece
///     [[x, y], ...] (m), the rest positions its mesh was made with},
///   "inputs" (optional, written by `tightfit optimize`): {"files": {path: content hash}},
///     the files the run read; not read here}
/// Doubles are written with round-trip precision, so a resumed run continues with
/// bit-identical numbers.
///
/// An iteration record: {"iteration", "objective", "terms": {name: w_j T_j},
///   "gradient_norm", "step_norm" (m), "max_point_move" (m), "max_solved_move" (m),
///   "step_factor",
///   "line_search_trials", "failed_solves", "newton_iterations", "hessian_shift" (N/m),
///   "seconds"}.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/design/optimization_state.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit {

/// One record; `term_names` name the entries of term_values (same length).
nlohmann::json iteration_json(const OptimizationIteration& it,
                              const std::vector<std::string>& term_names);
/// Reads a record written by iteration_json; `source` (file) and `path` (JSON pointer)
/// name it in InputErrors.
OptimizationIteration iteration_from_json(const nlohmann::json& j,
                                          const std::vector<std::string>& term_names,
                                          const std::string& source, const std::string& path = "");

nlohmann::json checkpoint_json(const OptimizationCheckpoint& c,
                               const std::vector<std::string>& term_names);
OptimizationCheckpoint checkpoint_from_json(const nlohmann::json& j,
                                            const std::vector<std::string>& term_names,
                                            const std::string& source);

/// Writes the checkpoint atomically (temporary file + rename).
void write_checkpoint(const std::filesystem::path& file, const OptimizationCheckpoint& c,
                      const std::vector<std::string>& term_names);
/// Reads a checkpoint; InputError names the file and what is wrong (also when its
/// objective terms differ from `term_names`).
OptimizationCheckpoint read_checkpoint(const std::filesystem::path& file,
                                       const std::vector<std::string>& term_names);

}  // namespace tightfit
