#pragma once
/// From a tensile tester's strip tests to a fabric file (scene/fabric_spec.hpp): the
/// recorded force and extension of strips cut along the grain (wale), across it (course)
/// and at 45° (bias), in loading and unloading cycles, become the measured knit's curves.
///
/// Input: CSV files (comma, semicolon or tab separated), a header row naming the columns
///   direction      wale | course | bias   (per row)
///   extension_mm   the clamps' travel from the gauge length (mm)
///   force_n        the force on the strip (N)
///   cycle          optional: the loading cycle the row belongs to (an integer)
/// in the order the tester recorded them. Without a `cycle` column the cycles are found
/// from the extension: a loading branch runs from a minimum of the extension to the next
/// maximum, an unloading branch back down (turns smaller than 2 % of the extension's range
/// are noise).
///
/// Fit: tension T = force / width (N/m), engineering strain ε = extension / gauge. Per
/// direction, the chosen cycle's loading (and unloading) branch is made monotone by an
/// isotonic regression (pool adjacent violators) and sampled at `points` strains evenly
/// spread up to the branch's largest strain; samples at zero tension (a slack strip) are
/// dropped, and each sample is kept strictly above the previous one.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tightfit {

/// One recorded row.
struct StripSample {
  std::string direction;    ///< "wale", "course" or "bias"
  double extension_mm = 0;  ///< mm
  double force_n = 0;       ///< N
  int cycle = 0;            ///< 1-based; 0 when the file has no cycle column
};

/// Reads the rows of one CSV file. InputError naming the file and line for a missing
/// column, a value that is not a number, an unknown direction or a negative extension.
std::vector<StripSample> read_strip_test_csv(const std::filesystem::path& file);

struct FabricFitOptions {
  double width_mm = 50.0;      ///< strip width
  double gauge_mm = 100.0;     ///< gauge length between the clamps
  int cycle = 0;               ///< 1-based cycle to fit; 0: the last complete one
  int points = 8;              ///< points per fitted curve (≥ 2)
  std::string name;            ///< the fabric's name
  double thickness_m = 0.0;    ///< 0: not given (the scene's default is used)
  double shear_n_per_m = 0.0;  ///< needed without bias samples
  double coupling = 0.0;       ///< c in [0, 1)
  std::string source;          ///< provenance text (the files read)
  std::string files;           ///< the files read, naming errors ("fabric fit" when empty)
};

/// One direction's data and fit, for the plot: the chosen cycle's samples (strain,
/// tension in N/m) and the fitted loading and unloading points (empty when none).
struct FittedDirection {
  std::string direction;
  std::vector<std::pair<double, double>> samples;
  std::vector<double> loading_strain, loading_tension;
  std::vector<double> unloading_strain, unloading_tension;
  int cycle = 0, cycles = 0;  ///< the cycle fitted, of how many
};

struct FabricFit {
  nlohmann::json fabric;                    ///< the fabric file's object
  std::vector<FittedDirection> directions;  ///< wale, course, then bias when given
  std::vector<std::string> warnings;        ///< e.g. a direction without an unloading branch
};

/// Fits the samples (of every file). InputError (naming `files`) when wale or course
/// has no samples, a cycle is missing, a branch has fewer than two points with tension,
/// or neither bias samples nor a shear stiffness are given. The result is checked by
/// the fabric reader (a fabric it would refuse is an error here).
FabricFit fit_fabric(const std::vector<StripSample>& samples, const FabricFitOptions& options);

}  // namespace tightfit
