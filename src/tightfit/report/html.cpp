#include "tightfit/report/html.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/xml_text.hpp"
#include "tightfit/report/data.hpp"
#include "tightfit/report/encoding.hpp"
#include "tightfit/report/modules.hpp"

#ifndef TIGHTFIT_REPORT_VIEWER_DIR
#error "TIGHTFIT_REPORT_VIEWER_DIR must be defined by the build (cmake/Dependencies.cmake)"
#endif
#ifndef TIGHTFIT_THREE_MODULE_JS
#error "TIGHTFIT_THREE_MODULE_JS must be defined by the build (cmake/Dependencies.cmake)"
#endif
#ifndef TIGHTFIT_THREE_ORBIT_CONTROLS_JS
#error "TIGHTFIT_THREE_ORBIT_CONTROLS_JS must be defined by the build (cmake/Dependencies.cmake)"
#endif

namespace tightfit {

namespace {

constexpr const char* kInstallHint =
    "; install the report's npm packages with scripts/install-deps.sh (npm ci --prefix report) "
    "or set the path in ReportOptions";

std::string read_asset(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot read the report's " + what + kInstallHint);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void require_file(const std::filesystem::path& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path.string(), what + " not found" + kInstallHint);
  }
}

/// Replaces the single occurrence of `marker` in `text` (InputError if it is missing).
void replace_marker(std::string& text, const std::string& marker, const std::string& with,
                    const std::filesystem::path& template_path) {
  const auto pos = text.find(marker);
  if (pos == std::string::npos) {
    throw InputError(template_path.string(), "the template lacks the marker " + marker);
  }
  text.replace(pos, marker.size(), with);
}

bool contains_script_end(const std::string& code) {
  std::string lower(code.size(), ' ');
  std::transform(code.begin(), code.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("</script") != std::string::npos;
}

}  // namespace

std::filesystem::path default_report_viewer_dir() { return TIGHTFIT_REPORT_VIEWER_DIR; }
std::filesystem::path default_three_module_path() { return TIGHTFIT_THREE_MODULE_JS; }
std::filesystem::path default_orbit_controls_path() { return TIGHTFIT_THREE_ORBIT_CONTROLS_JS; }

std::string render_report_html(const FitView& view, const ReportOptions& options,
                               const std::string& source) {
  validate_fit_view(view, source);
  require_file(options.three_module, "three.js module");
  require_file(options.orbit_controls, "three.js OrbitControls addon");
  const auto template_path = options.viewer_dir / "template.html";
  const auto viewer_path = options.viewer_dir / "viewer.js";
  std::string html = read_asset(template_path, "HTML template");
  const std::string viewer = read_asset(viewer_path, "viewer script");
  if (contains_script_end(viewer)) {
    throw InputError(viewer_path.string(), "the viewer script must not contain '</script'");
  }

  const nlohmann::json import_map = inline_module_import_map(
      {{"three", options.three_module},
       {"three/addons/controls/OrbitControls.js", options.orbit_controls}});
  const nlohmann::json data = report_data_json(view, options.colorings, options.title, source);

  const std::string title = xml_escape(options.title);
  for (std::size_t pos = 0; (pos = html.find("{{TITLE}}", pos)) != std::string::npos;) {
    html.replace(pos, 9, title);
    pos += title.size();
  }
  replace_marker(html, "<!-- tightfit:importmap -->",
                 "<script type=\"importmap\">" + json_for_script(import_map) + "</script>",
                 template_path);
  replace_marker(html, "<!-- tightfit:data -->",
                 "<script type=\"application/json\" id=\"tightfit-data\">" + json_for_script(data) +
                     "</script>",
                 template_path);
  replace_marker(html, "<!-- tightfit:viewer -->",
                 "<script type=\"module\">\n" + viewer + "\n</script>", template_path);
  return html;
}

void write_report_html(const std::filesystem::path& path, const FitView& view,
                       const ReportOptions& options) {
  // Rendered inside the write so that a NaN in the data names the file (finite_output.hpp).
  write_file_atomically(
      path, [&](std::ostream& out) { out << render_report_html(view, options, path.string()); });
}

}  // namespace tightfit
