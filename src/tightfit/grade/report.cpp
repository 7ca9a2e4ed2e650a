#include "tightfit/grade/report.hpp"

#include <algorithm>
#include <sstream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/xml_text.hpp"
#include "tightfit/patterns/text.hpp"

namespace tightfit {
namespace {

/// Colour of size `k` (distinct for the first eight, then repeating).
const char* size_colour(size_t k) {
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
  return colours[k % 8];
}

/// A number of `j[key]` with `digits` decimals, or "–".
std::string cell(const nlohmann::json& j, const char* key, int digits) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return "–";
  return fixed(j[key].get<double>(), digits);
}

/// "min / median / max" of a statistics object.
std::string range_cell(const nlohmann::json& j, int digits) {
  if (!j.is_object()) return "–";
  return cell(j, "min", digits) + " / " + cell(j, "median", digits) + " / " +
         cell(j, "max", digits);
}

/// One inline SVG of nest group `g`: every size's sew line, in the colour of body
/// `colour_index[size]`.
std::string nest_svg(const Nest& nest, int g, const std::vector<size_t>& colour_index) {
  Vec2 lo = Vec2::Constant(1e30), hi = Vec2::Constant(-1e30);
  for (size_t p = 0; p < nest.pattern.pieces.size(); ++p) {
    if (nest.group[p] != g) continue;
    for (Eigen::Index i = 0; i < nest.pattern.pieces[p].rest.rows(); ++i) {
      lo = lo.cwiseMin(Vec2(nest.pattern.pieces[p].rest.row(i).transpose()) * 1000.0);
      hi = hi.cwiseMax(Vec2(nest.pattern.pieces[p].rest.row(i).transpose()) * 1000.0);
    }
  }
  if (lo.x() > hi.x()) return "";
  const double pad = 10.0, w = hi.x() - lo.x() + 2 * pad, h = hi.y() - lo.y() + 2 * pad;
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << fixed(w, 1) << " "
      << fixed(h, 1) << "\" style=\"width:" << fixed(std::min(w, 420.0), 0) << "px\">";
  // The grain line: the vertical through the origin (every piece's grain points up).
  out << "<line x1=\"" << fixed(pad - lo.x(), 1) << "\" y1=\"0\" x2=\"" << fixed(pad - lo.x(), 1)
      << "\" y2=\"" << fixed(h, 1)
      << "\" stroke=\"#999\" stroke-dasharray=\"4 3\" stroke-width=\"0.6\"/>";
  for (size_t p = 0; p < nest.pattern.pieces.size(); ++p) {
    if (nest.group[p] != g) continue;
    const PatternPiece& piece = nest.pattern.pieces[p];
    for (const auto& loop : piece.loops()) {
      out << "<polygon fill=\"none\" stroke-width=\"0.8\" stroke=\""
          << size_colour(colour_index[static_cast<size_t>(nest.size[p])]) << "\" points=\"";
      for (int v : loop)
        out << fixed(piece.rest(v, 0) * 1000.0 - lo.x() + pad, 1) << ","
            << fixed(hi.y() - piece.rest(v, 1) * 1000.0 + pad, 1) << " ";
      out << "\"><title>" << xml_escape(piece.name) << "</title></polygon>";
    }
  }
  out << "</svg>";
  return out.str();
}

}  // namespace

void write_grade_report(const std::filesystem::path& file, const GradeSummary& summary,
                        const Nest* nest) {
  const nlohmann::json& j = summary.json;
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>tightfit grading — "
    << xml_escape(j.value("design", std::string())) << "</title><style>"
    << "body{font-family:sans-serif;margin:2em;color:#222}table{border-collapse:collapse;margin:"
       "1em 0}"
    << "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f3f3f3}"
    << "td:first-child,th:first-child{text-align:left}.failed{color:#b00}.nest{display:inline-"
       "block;"
    << "vertical-align:top;margin:0 1.5em 1.5em "
       "0}.swatch{display:inline-block;width:1em;height:0.6em;"
    << "margin:0 0.3em 0 1em}</style></head><body>\n";
  h << "<h1>Grading of " << xml_escape(j.value("design", std::string()))
    << "</h1>\n<p>Bodies: " << xml_escape(j.value("bodies_file", std::string())) << " — "
    << j["counts"]["done"] << " of " << j["counts"]["bodies"] << " graded, "
    << j["counts"]["failed"] << " failed, " << j["counts"]["not_run"] << " not run; "
    << xml_escape(j.value("date", std::string())) << ".</p>\n";

  h << "<h2>Sizes</h2>\n<table><tr><th>body</th><th>status</th><th>objective ratio</th>"
    << "<th>iterations</th><th>layout s</th><th>initial solve s</th><th>iterations s</th>"
    << "<th>largest stretch (min / median / max)</th><th>smallest stretch (min / median / max)</th>"
    << "<th>pressure mmHg (min / median / max)</th><th>pressure spread</th><th>lift-off "
       "share</th></tr>\n";
  for (size_t k = 0; k < summary.bodies.size(); ++k) {
    const GradedBody& b = summary.bodies[k];
    const nlohmann::json& e = b.entry;
    h << "<tr><td><span class=\"swatch\" style=\"background:" << size_colour(k)
      << ";margin-left:0\"></span>" << xml_escape(b.name) << "</td><td"
      << (b.status == "failed" ? " class=\"failed\"" : "") << ">" << xml_escape(b.status)
      << (b.error.empty() ? "" : ": " + xml_escape(b.error)) << "</td>";
    if (b.status != "done") {
      h << "<td colspan=\"10\"></td></tr>\n";
      continue;
    }
    const nlohmann::json& s = e["seconds"];
    h << "<td>" << cell(e["objective"], "ratio", 3) << "</td><td>"
      << (e["iterations"].is_number() ? e["iterations"].dump() : "–") << "</td><td>"
      << cell(s, "layout", 1) << "</td><td>" << cell(s, "initial_solve", 1) << "</td><td>"
      << cell(s, "iterations", 1) << "</td><td>" << range_cell(e["stretch_max"], 3) << "</td><td>"
      << range_cell(e["stretch_min"], 3) << "</td><td>" << range_cell(e["pressure_mmhg"], 1)
      << "</td><td>" << cell(e, "pressure_spread", 3) << "</td><td>" << cell(e, "lift_off_share", 3)
      << "</td></tr>\n";
  }
  h << "</table>\n<p>Stretch: principal stretches of the fabric on the body (1 = unstretched), "
       "pressure: on the body under the garment, both area-weighted medians over the "
       "garment.</p>\n";

  // Girths and negative ease at the measurement levels, size by size.
  std::vector<std::string> levels;  // in the order of the first body that has them
  for (const GradedBody& b : summary.bodies)
    if (b.status == "done" && b.entry.contains("measurements"))
      for (const auto& m : b.entry["measurements"])
        if (m["name"].is_string() &&
            std::find(levels.begin(), levels.end(), m["name"].get<std::string>()) == levels.end())
          levels.push_back(m["name"].get<std::string>());
  if (!levels.empty()) {
    h << "<h2>Girths and negative ease</h2>\n<table><tr><th>level</th>";
    for (const GradedBody& b : summary.bodies)
      if (b.status == "done") h << "<th>" << xml_escape(b.name) << "</th>";
    h << "</tr>\n";
    for (const std::string& level : levels) {
      h << "<tr><td>" << xml_escape(level) << "</td>";
      for (const GradedBody& b : summary.bodies) {
        if (b.status != "done") continue;
        h << "<td>";
        for (const auto& m : b.entry["measurements"])
          if (m["name"] == level && m["body_circumference_m"].is_number() &&
              m["ease_percent"].is_number())
            h << fixed(100.0 * m["body_circumference_m"].get<double>(), 1) << " cm, "
              << fixed(m["ease_percent"].get<double>(), 0) << " %";
        h << "</td>";
      }
      h << "</tr>\n";
    }
    h << "</table>\n<p>Body circumference at each level (cm, on the body before the garment "
         "presses it) and the pattern's negative ease there, (pattern − body) / body; the "
         "levels are those of each body's measurement table (docs/guide/outputs.md, \"Measurements "
         "and negative ease\").</p>\n";
  }

  // Seam lengths and their size-to-size change.
  h << "<h2>Seam lengths (mm) and change from the size before</h2>\n<table><tr><th>seam</th>";
  std::vector<std::string> done;
  for (const GradedBody& b : summary.bodies)
    if (b.status == "done") done.push_back(b.name);
  for (const std::string& name : done) h << "<th>" << xml_escape(name) << "</th>";
  h << "</tr>\n";
  for (const auto& seam : j["seams"]) {
    h << "<tr><td>" << xml_escape(seam["name"].get<std::string>()) << "</td>";
    for (const std::string& name : done) {
      h << "<td>";
      if (seam["length_mm"].contains(name)) h << fixed(seam["length_mm"][name].get<double>(), 1);
      if (seam["change_mm"].contains(name)) {
        const double d = seam["change_mm"][name].get<double>();
        h << " (" << (d >= 0 ? "+" : "") << fixed(d, 1) << ")";
      }
      h << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table>\n";

  if (nest) {
    h << "<h2>Nest</h2>\n<p>Every size's pieces on top of each other, grain lines up (dashed), "
         "aligned at "
      << xml_escape(nest->alignment == "centroid" ? "the area centroid"
                                                  : "the start of " + nest->alignment)
      << "; sew lines in mm. Sizes:";
    for (size_t k = 0; k < summary.bodies.size(); ++k)
      if (summary.bodies[k].status == "done")
        h << "<span class=\"swatch\" style=\"background:" << size_colour(k) << "\"></span>"
          << xml_escape(summary.bodies[k].name);
    h << ". Exports: <a href=\"nest.svg\">nest.svg</a>, <a href=\"nest.pdf\">nest.pdf</a>, "
         "<a href=\"nest.dxf\">nest.dxf</a>.</p>\n";
    std::vector<size_t> colour_index;  // nest size -> its body's row in the table
    for (const std::string& name : nest->size_names)
      for (size_t k = 0; k < summary.bodies.size(); ++k)
        if (summary.bodies[k].name == name) colour_index.push_back(k);
    for (size_t g = 0; g < nest->piece_names.size(); ++g)
      h << "<div class=\"nest\"><h3>" << xml_escape(nest->piece_names[g]) << "</h3>"
        << nest_svg(*nest, static_cast<int>(g), colour_index) << "</div>\n";
  }
  h << "</body></html>\n";
  write_text_atomically(file, h.str());
}

}  // namespace tightfit
