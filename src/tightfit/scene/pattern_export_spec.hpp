#pragma once
/// The scene's "patterns" section: how the pattern files are drawn (seam allowances,
/// notches, corners, truing, label texts). SI inside (m); the writers use mm.
///
///   "patterns": {"seam_allowance": 0.01, "seam_allowances": {"NAME": 0.015},
///                "notch_depth": 0.004, "notch_spacing": 0.1,
///                "notches": {"SEAM": "single" | "double"},
///                "corner_style": "mitre" | "round", "true_tolerance": 0.0003,
///                "style": "…", "size": "…"}
///
/// Seam names are only known once the garment is built: check_pattern_export_spec
/// checks them against the pattern.
#include <map>
#include <string>

#include "tightfit/common/json_fields.hpp"
#include "tightfit/garment/pattern.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

struct PatternExportSpec {
  /// seam_allowance, seam_allowances, notch_depth, notch_spacing, seam_notch_styles (the
  /// explicit "notches" rules), corner_style and true_tolerance as given (defaults
  /// otherwise); the other fields keep their defaults.
  PatternExportOptions options;
  /// "style" and "size" (empty when not given: the caller picks defaults).
  std::string style;
  std::string size;
  std::string file;       ///< the scene file (for messages)
  std::string json_path;  ///< JSON pointer of the section, "/patterns"
};

/// Parses the "patterns" object `f` strictly (unknown keys, wrong types, negative
/// lengths, unknown notch styles are InputErrors naming the file and JSON path).
PatternExportSpec parse_pattern_export_spec(JsonFields& f);

/// InputError (naming spec.file and the JSON path, e.g.
/// "/patterns/seam_allowances/NAME") when "seam_allowances" names neither a seam nor a
/// pinned boundary of `pattern`, or "notches" names no seam.
void check_pattern_export_spec(const PatternExportSpec& spec, const Pattern& pattern);

}  // namespace tightfit
