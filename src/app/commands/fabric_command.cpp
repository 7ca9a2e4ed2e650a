/// `tightfit fabric fit CSV... --width MM --gauge MM --out FABRIC.json`: turns a tensile
/// tester's strip tests (scene/fabric_fit.hpp) into a fabric file for scenes
/// ("fabric": "FABRIC.json") and a plot of the data and the fitted curves beside it
/// (FABRIC.svg). Both files are new: an existing one is refused unless --force (and a
/// folder or a symbolic link always), and they appear together or not at all.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "command_registry.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/report/fabric_plot.hpp"
#include "tightfit/scene/fabric_fit.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

struct FabricFitCommand {
  std::vector<std::string> files;
  std::string out;
  bool force = false;
  FabricFitOptions fit;
  double thickness_mm = 0.0;
};

/// Refuses to replace `path` unless `force`, and a folder or symbolic link always.
void check_target(const fs::path& path, bool force) {
  const fs::file_status status = fs::symlink_status(path);
  if (!fs::exists(status)) return;
  if (fs::is_symlink(status) || !fs::is_regular_file(status))
    throw InputError(path.string(), "exists and is not a regular file: not replaced");
  if (!force) throw InputError(path.string(), "exists: not replaced (--force replaces it)");
}

void write_together(const fs::path& json_path, const std::string& json_text,
                    const fs::path& svg_path, const std::string& svg_text) {
  const fs::path json_tmp = temporary_path_for(json_path);
  fs::path svg_tmp;
  try {
    std::ofstream(json_tmp, std::ios::binary) << json_text;
    svg_tmp = temporary_path_for(svg_path);
    std::ofstream(svg_tmp, std::ios::binary) << svg_text;
    commit_temporary(svg_tmp, svg_path);
    svg_tmp.clear();
    commit_temporary(json_tmp, json_path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(json_tmp, ignored);
    if (!svg_tmp.empty()) fs::remove(svg_tmp, ignored);
    throw;
  }
}

void run_fit(FabricFitCommand o) {
  if (o.files.empty()) throw InputError("fabric fit", "give at least one CSV file");
  const fs::path out(o.out);
  if (out.extension() != ".json")
    throw InputError(o.out, "--out names the fabric file to write, e.g. my_knit.json");
  fs::path svg = out;
  svg.replace_extension(".svg");
  check_target(out, o.force);
  check_target(svg, o.force);
  std::vector<StripSample> samples;
  std::string read;
  for (const std::string& file : o.files) {
    const std::vector<StripSample> rows = read_strip_test_csv(file);
    samples.insert(samples.end(), rows.begin(), rows.end());
    read += (read.empty() ? "" : ", ") + fs::path(file).filename().string();
  }
  if (o.fit.name.empty()) o.fit.name = out.stem().string();
  o.fit.thickness_m = o.thickness_mm * 1e-3;
  char settings[160];
  std::snprintf(settings, sizeof settings, "strips %g mm wide, gauge length %g mm", o.fit.width_mm,
                o.fit.gauge_mm);
  o.fit.source = "fitted by tightfit fabric fit from " + read + " (" + settings + ")";
  o.fit.files = read;
  const FabricFit fit = fit_fabric(samples, o.fit);
  for (const std::string& w : fit.warnings) std::printf("  note: %s\n", w.c_str());
  write_together(out, fit.fabric.dump(2) + "\n", svg,
                 fabric_fit_svg(fit, o.fit.name + ": strip tests and fitted curves"));
  for (const FittedDirection& d : fit.directions)
    std::printf("  %-6s cycle %d of %d: %zu loading points up to %.1f %% (%.1f N/m)%s\n",
                d.direction.c_str(), d.cycle, d.cycles, d.loading_strain.size(),
                100.0 * d.loading_strain.back(), d.loading_tension.back(),
                d.unloading_strain.size() >= 2 ? ", unloading" : "");
  std::printf("  %s\n  %s\n", out.c_str(), svg.c_str());
}

const CommandRegistration kFabric{
    "fabric", [](CLI::App& root) {
      CLI::App* fabric = root.add_subcommand("fabric", "Fabrics: fit strip tests to a fabric file");
      fabric->require_subcommand(1);
      fabric->footer(
          "Example:\n  tightfit fabric fit tests.csv --width 50 --gauge 100 "
          "--out my_knit.json");
      auto [cmd, o] = add_command<FabricFitCommand>(
          *fabric,
          {"fit",
           "Fit a measured knit's curves to a tensile tester's strip tests: CSV files with the "
           "columns direction (wale, course or bias), extension_mm, force_n and optionally "
           "cycle, in recording order. Writes the fabric file (--out, for a scene's \"fabric\") "
           "and a plot of the data and the fitted curves beside it (the same name, .svg). The "
           "last complete cycle is fitted unless --cycle says otherwise; its unloading branch "
           "becomes the unloading curve the worn garment follows.",
           "Example:\n  tightfit fabric fit strips.csv --width 50 --gauge 100 --shear 30 "
           "--out power_net.json"},
          [](const FabricFitCommand& options) { run_fit(options); });
      cmd.add_option("csv", o.files, "Strip-test CSV files")->required();
      cmd.add_option("--out", o.out, "The fabric file to write (.json); the plot goes beside it")
          ->required();
      cmd.add_flag("--force", o.force, "Replace existing files of those names");
      cmd.add_option("--width", o.fit.width_mm, "Strip width (mm)")->required();
      cmd.add_option("--gauge", o.fit.gauge_mm, "Gauge length between the clamps (mm)")->required();
      cmd.add_option("--name", o.fit.name, "The fabric's name (default: the file's stem)");
      cmd.add_option("--thickness", o.thickness_mm, "The fabric's thickness (mm)");
      cmd.add_option("--shear", o.fit.shear_n_per_m,
                     "In-plane shear stiffness (N/m), needed when there are no bias strips");
      cmd.add_option("--coupling", o.fit.coupling, "Lateral coupling c in [0, 1) (default 0)");
      cmd.add_option("--cycle", o.fit.cycle, "The cycle to fit, from 1 (default: the last)");
      cmd.add_option("--points", o.fit.points, "Points per fitted curve (default 8)");
    }};

}  // namespace
}  // namespace tightfit::app
