#include "tightfit/patterns/json.hpp"

#include <nlohmann/json.hpp>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/validate.hpp"
#include "tightfit/report/seam_statistics.hpp"
#include "tightfit/scene/pattern_record.hpp"

#include <stdexcept>

namespace tightfit {
namespace {

using nlohmann::json;

json json_point(const Vec2& q) { return json::array({q.x(), q.y()}); }

json polygon(const Polygon2& polygon) {
  json out = json::array();
  for (const Vec2& q : polygon) out.push_back(json_point(q));
  return out;
}

json openings_mm(const PieceDrawing& drawing) {
  json out = json::array();
  for (const Polygon2& hole : drawing.holes) out.push_back(polygon(hole));
  return out;
}

/// Adds the informative name of the piece a seam side or pinned boundary lies on.
void add_piece_name(const Pattern& pattern, json& side) {
  side["piece_name"] = pattern.pieces[side["piece"].get<size_t>()].name;
}

/// Adds the outlines, notches, allowances and quantity of `drawing` to the record of its
/// piece.
void add_drawing(const PieceDrawing& drawing, json& piece) {
  json notches = json::array();
  for (const Notch& n : drawing.notches) {
    notches.push_back({{"seam", n.seam},
                       {"side", n.side == 0 ? "a" : "b"},
                       {"index", n.index},
                       {"sew", json_point(n.sew)},
                       {"cut", json_point(n.cut)},
                       {"style", n.style == NotchStyle::kDouble ? "double" : "single"}});
  }
  piece["quantity"] = drawing.quantity;
  piece["sew_line_mm"] = polygon(drawing.sew_line);
  piece["cut_line_mm"] = polygon(drawing.cut_line);
  piece["openings_mm"] = openings_mm(drawing);
  piece["allowance_mm"] = drawing.allowance;
  piece["grain_line_mm"] =
      json::array({json_point(drawing.grain_start), json_point(drawing.grain_end)});
  piece["notches_mm"] = notches;
}

}  // namespace

void write_pieces_json(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path,
                       const std::vector<SeamStatistics>* fit_seams) {
  const std::vector<PieceDrawing> drawings = draw_pattern_pieces(pattern, options, path.string());
  if (fit_seams && fit_seams->size() != pattern.seams.size())
    throw std::invalid_argument("write_pieces_json: one fit statistic per seam expected");
  json root = pattern_record_json(pattern);
  root["format"] = "tightfit-pieces";
  root["version"] = 1;
  root["units"] = {{"rest", "m"}, {"outlines", "mm"}};
  root["seam_allowance_m"] = options.seam_allowance;
  for (size_t p = 0; p < pattern.pieces.size(); ++p) add_drawing(drawings[p], root["pieces"][p]);
  const std::vector<SeamStatistics> lengths = pattern_seam_statistics(pattern);
  for (size_t k = 0; k < pattern.seams.size(); ++k) {
    json& entry = root["seams"][k];
    add_piece_name(pattern, entry["a"]);
    add_piece_name(pattern, entry["b"]);
    entry["length_a_mm"] = 1000.0 * lengths[k].length_a;
    entry["length_b_mm"] = 1000.0 * lengths[k].length_b;
    entry["mismatch_mm"] = 1000.0 * lengths[k].mismatch();
    if (fit_seams) {
      json fit = seam_statistics_json((*fit_seams)[k]);
      for (const char* key :
           {"name", "piece_a", "piece_b", "length_a_mm", "length_b_mm", "mismatch_mm"})
        fit.erase(key);
      entry["fit"] = fit;
    }
  }
  for (json& pin : root["pinned"]) add_piece_name(pattern, pin);
  write_json_atomically(path, root, 1);
}

Pattern read_pieces_json(const std::filesystem::path& path) {
  const std::string source = path.string();
  const json root = read_json_file(source);
  JsonFields f(root, source, "");
  if (f.string("format") != "tightfit-pieces") f.fail("expected \"tightfit-pieces\"", "format");
  if (f.integer("version") != 1) f.fail("unsupported version (expected 1)", "version");
  PatternRecordExtraKeys derived;
  derived.root = {"format", "version", "units", "seam_allowance_m"};
  derived.piece = {"quantity",     "sew_line_mm",   "cut_line_mm", "openings_mm",
                   "allowance_mm", "grain_line_mm", "notches_mm"};
  derived.seam = {"length_a_mm", "length_b_mm", "mismatch_mm", "fit"};
  derived.side = {"piece_name"};
  Pattern pattern = pattern_record_from_json(root, source, "", derived);
  validate_pattern(pattern, source);
  return pattern;
}

}  // namespace tightfit
