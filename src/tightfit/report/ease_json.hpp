#pragma once
/// The ease table (garment/ease_table.hpp) as JSON, for result.json ("measurements")
/// and the report. One object per level:
///
///   {"name": "calf.L", "origin": "skeleton" | "scene" | "planes",
///    "anchor": "lowerleg01.L at 0.45", "point": [x, y, z] (m), "normal": [x, y, z],
///    "status": "measured" | "skipped", "reason": "…" (skipped only),
///    "body_circumference_m", "pattern_circumference_m", "garment_circumference_m",
///    "ease_percent" ((pattern − body) / body × 100), "fitted_stretch" (garment /
///    pattern), "pieces": [{"piece": NAME, "pattern_width_m"}]}   (measured only)
#include <nlohmann/json.hpp>

#include "tightfit/garment/ease_table.hpp"

namespace tightfit {

/// The levels of `table` as a JSON array (see above).
nlohmann::json ease_table_json(const EaseTable& table);

}  // namespace tightfit
