#pragma once
/// The run outputs of the public API (api/run_outputs.hpp) under the names the command
/// files use.
#include "tightfit/api/run_outputs.hpp"

namespace tightfit::app {

using api::compute_json;
using api::kMaxPatternPieces;
using api::mark_best_iteration;
using api::report_summary;
using api::run_identity_json;
using api::write_fit_run_outputs;
using api::write_layout_run_outputs;

}  // namespace tightfit::app
