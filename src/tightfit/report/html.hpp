#pragma once
/// The fit report: one self-contained report.html that opens offline (file://, no
/// network): a three.js 3D view of body and garment with orbit controls and switchable
/// colour maps with a legend (units), the pattern pieces in 2D coloured by the same
/// field, the objective history as a small plot, per-piece statistics (pressure in Pa
/// and mmHg, slack/wrinkled area shares, lift-off area) and the scene parameters.
///
/// The page is report/template.html with report/viewer.js, the data (report_data.hpp)
/// and three.js inlined (report_modules.hpp). three.js comes from npm (pinned in
/// report/package.json, installed into report/node_modules by scripts/install-deps.sh);
/// its paths are fixed at build time and can be overridden in ReportOptions.
#include <filesystem>
#include <string>
#include <vector>

#include "tightfit/report/fit_colormap.hpp"
#include "tightfit/report/fit_view.hpp"

namespace tightfit {

/// Build-time locations (report/ in the source tree and three.js under its node_modules).
std::filesystem::path default_report_viewer_dir();
std::filesystem::path default_three_module_path();
std::filesystem::path default_orbit_controls_path();

struct ReportOptions {
  std::string title = "tightfit fit report";
  /// Colour maps offered in the viewer, the first shown initially. Those whose field
  /// the fit lacks are listed on the page as unavailable.
  std::vector<FieldColoring> colorings = standard_colorings();
  /// Folder with template.html and viewer.js.
  std::filesystem::path viewer_dir = default_report_viewer_dir();
  /// three.js ES module (build/three.module.js; its relative imports are inlined too).
  std::filesystem::path three_module = default_three_module_path();
  /// three.js OrbitControls addon (examples/jsm/controls/OrbitControls.js).
  std::filesystem::path orbit_controls = default_orbit_controls_path();
};

/// The report's HTML text. InputError for an invalid view or a missing viewer/three.js
/// file (the message says how to install it).
std::string render_report_html(const FitView& view, const ReportOptions& options = {},
                               const std::string& source = "report.html");

/// Writes render_report_html to `path` atomically.
void write_report_html(const std::filesystem::path& path, const FitView& view,
                       const ReportOptions& options = {});

}  // namespace tightfit
