#include "tightfit/scene/pattern_export_spec.hpp"

#include <set>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {

PatternExportSpec parse_pattern_export_spec(JsonFields& f) {
  PatternExportSpec spec;
  spec.file = f.source();
  spec.json_path = f.path();
  PatternExportOptions& o = spec.options;
  o.seam_allowance = f.positive("seam_allowance", o.seam_allowance, true);
  if (auto allowances = f.object("seam_allowances")) {
    for (const auto& item : f.raw("seam_allowances").items())
      o.seam_allowances[item.key()] = allowances->positive(item.key(), {}, true);
    allowances->finish();
  }
  o.notch_depth = f.positive("notch_depth", o.notch_depth, true);
  o.notch_spacing = f.positive("notch_spacing", o.notch_spacing, true);
  if (auto notches = f.object("notches")) {
    for (const auto& item : f.raw("notches").items()) {
      o.seam_notch_styles[item.key()] =
          notches->choice(item.key(), {"single", "double"}) == "double" ? NotchStyle::kDouble
                                                                        : NotchStyle::kSingle;
    }
    notches->finish();
  }
  o.corner_style = f.choice("corner_style", {"mitre", "round"}, "mitre") == "round"
                       ? CornerStyle::kRound
                       : CornerStyle::kMitre;
  o.true_tolerance = f.positive("true_tolerance", o.true_tolerance, true);
  spec.style = f.string("style", std::string());
  spec.size = f.string("size", std::string());
  f.finish();
  return spec;
}

void check_pattern_export_spec(const PatternExportSpec& spec, const Pattern& pattern) {
  std::set<std::string> seams;
  std::set<std::string> boundaries;
  for (const Seam& seam : pattern.seams) seams.insert(seam.name);
  for (const PinnedBoundary& pin : pattern.pinned) boundaries.insert(pin.name);
  for (const auto& entry : spec.options.seam_allowances) {
    if (!seams.count(entry.first) && !boundaries.count(entry.first)) {
      std::string where = spec.json_path + "/seam_allowances/" + entry.first;
      throw InputError(spec.file,
                       where + ": the garment has no seam or pinned boundary of that name");
    }
  }
  for (const auto& entry : spec.options.seam_notch_styles) {
    if (!seams.count(entry.first)) {
      std::string where = spec.json_path + "/notches/" + entry.first;
      throw InputError(spec.file, where + ": the garment has no seam of that name");
    }
  }
}

}  // namespace tightfit
