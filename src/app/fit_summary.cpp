#include "fit_summary.hpp"

#include <cstdio>

namespace tightfit::app {
namespace {

/// Shares of the garment's area above which wrinkled or slack fabric, and fabric lifting
/// off the body, are warned about.
constexpr double kLooseWarningShare = 0.10;
constexpr double kLiftOffWarningShare = 0.01;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

/// A share of the garment in percent: one decimal, "under 0.1 %" for a small one.
std::string percent(double share) {
  return share > 0.0 && share < 0.001 ? std::string("under 0.1 %")
                                      : format("%.1f %%", 100.0 * share);
}

double number(const nlohmann::json& j, const char* key, double fallback = 0.0) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

}  // namespace

std::vector<std::string> fit_summary_lines(const nlohmann::json& result,
                                           const std::filesystem::path& report) {
  std::vector<std::string> lines;
  if (!result.contains("fit") || !result["fit"].is_object()) return lines;
  const nlohmann::json& fit = result["fit"];
  const nlohmann::json& p = fit.value("pressure_mmhg", nlohmann::json::object());
  const nlohmann::json& share = fit.value("area_share", nlohmann::json::object());
  const nlohmann::json& smax = fit.value("stretch_max", nlohmann::json::object());
  lines.push_back(format("pressure %.1f / %.1f / %.1f mmHg (min / median / max)", number(p, "min"),
                         number(p, "median"), number(p, "max")));
  lines.push_back(format("fabric stretched %.0f %% (median), up to %.0f %%; taut %.0f %%",
                         100.0 * (number(smax, "median", 1.0) - 1.0),
                         100.0 * (number(smax, "max", 1.0) - 1.0), 100.0 * number(share, "taut")) +
                  format(", wrinkled %.0f %%, slack %.0f %%", 100.0 * number(share, "wrinkled"),
                         100.0 * number(share, "slack")));
  if (fit.contains("pressure_regions") && fit["pressure_regions"].is_array())
    for (const nlohmann::json& r : fit["pressure_regions"]) {
      const nlohmann::json& t = r.value("target_mmhg", nlohmann::json::object());
      const nlohmann::json& rp = r.value("pressure_mmhg", nlohmann::json());
      std::string line = r.value("name", std::string("region")) + ": ";
      line += rp.is_object() ? format("median %.1f mmHg", number(rp, "median")) : "no pressure";
      line += format(" (target %.0f to %.0f mmHg), ", number(t, "min"), number(t, "max"));
      line += format("%.0f %% of its area in target", 100.0 * number(r, "share_in_target"));
      lines.push_back(line);
    }
  const double above = number(fit, "pressure_above_40mmhg_share");
  if (above > 0.0)
    lines.push_back("warning: " + percent(above) +
                    format(" of the garment presses harder than 40 mmHg (up to %.0f mmHg): a "
                           "risk for skin and circulation",
                           number(p, "max")));
  const double lift = number(fit, "lift_off_share");
  if (lift > kLiftOffWarningShare)
    lines.push_back("warning: " + percent(lift) +
                    " of the garment lifts off the body (negative pressure): it does not lie "
                    "on the skin there");
  const double loose = number(share, "wrinkled") + number(share, "slack");
  if (loose > kLooseWarningShare)
    lines.push_back(
        format("warning: %.0f %% of the garment is wrinkled or slack, not stretched "
               "both ways: a skintight garment should be taut",
               100.0 * loose));
  lines.push_back("open " + report.string() + " to see the fit, the pattern and the numbers");
  return lines;
}

void print_fit_summary(const nlohmann::json& result, const std::filesystem::path& report) {
  for (const std::string& line : fit_summary_lines(result, report))
    std::printf("  %s\n", line.c_str());
}

}  // namespace tightfit::app
