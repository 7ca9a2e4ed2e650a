#include "tightfit/report/ease_json.hpp"

namespace tightfit {

nlohmann::json ease_table_json(const EaseTable& table) {
  nlohmann::json levels = nlohmann::json::array();
  for (const LevelMeasurement& m : table.levels) {
    const MeasurementLevel& l = m.level;
    nlohmann::json j = {{"name", l.name},
                        {"origin", l.origin},
                        {"anchor", l.anchor},
                        {"point", {l.point.x(), l.point.y(), l.point.z()}},
                        {"normal", {l.normal.x(), l.normal.y(), l.normal.z()}}};
    if (!m.skipped.empty()) {
      j["status"] = "skipped";
      j["reason"] = m.skipped;
    } else {
      j["status"] = "measured";
      j["body_circumference_m"] = m.body_circumference;
      j["pattern_circumference_m"] = m.pattern_circumference;
      j["garment_circumference_m"] = m.garment_circumference;
      j["ease_percent"] = m.ease_percent();
      j["fitted_stretch"] = m.fitted_stretch();
      nlohmann::json pieces = nlohmann::json::array();
      for (const PieceWidth& p : m.pieces)
        pieces.push_back({{"piece", p.piece}, {"pattern_width_m", p.width}});
      j["pieces"] = pieces;
    }
    levels.push_back(std::move(j));
  }
  return levels;
}

}  // namespace tightfit
