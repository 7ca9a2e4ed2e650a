#pragma once
/// The closing lines of a run that simulates (simulate, optimize): what came out in a
/// pattern maker's terms — the pressure, the stretch range and the regimes, per pressure
/// region its median against the target and the share of its area in target — warnings
/// for pressure above 40 mmHg, lift-off and fabric that is not taut, and the report to
/// open.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tightfit::app {

/// The lines (without leading spaces or newlines) for `result` (result.json's document)
/// of a run whose report is `report`.
std::vector<std::string> fit_summary_lines(const nlohmann::json& result,
                                           const std::filesystem::path& report);

/// Prints fit_summary_lines, each indented by two spaces.
void print_fit_summary(const nlohmann::json& result, const std::filesystem::path& report);

}  // namespace tightfit::app
