#include "tightfit/grade/summary.hpp"

#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/version.hpp"
#include "tightfit/grade/status.hpp"
#include "tightfit/patterns/json.hpp"

namespace tightfit {
namespace {

namespace fs = std::filesystem;

/// `j[key]` or null.
nlohmann::json member(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) ? j[key] : nlohmann::json();
}

double number_or(const nlohmann::json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

/// The entry of a done body from its result.json, history.json and pieces.json.
void read_done_body(GradedBody& body, const fs::path& folder) {
  const nlohmann::json result = read_json_file((folder / "result.json").string());
  const nlohmann::json history = read_json_file((folder / "history.json").string());
  const nlohmann::json pieces = read_json_file((folder / "pieces.json").string());
  body.pattern = read_pieces_json(folder / "pieces.json");
  nlohmann::json& e = body.entry;
  const nlohmann::json o = member(result, "optimization");
  const double initial = number_or(o, "objective_initial", 0.0);
  const double final_value = number_or(o, "objective_final", 0.0);
  e["objective"] = {{"initial", initial},
                    {"final", final_value},
                    {"ratio", initial > 0.0 ? final_value / initial : 0.0}};
  e["iterations"] = member(o, "iterations");
  e["stop_reason"] = member(o, "stop_reason");
  const nlohmann::json seconds = member(result, "seconds");
  const nlohmann::json its = member(history, "iterations");
  const double first =
      its.is_array() && !its.empty() ? number_or(its.front(), "seconds", 0.0) : 0.0;
  const double last = its.is_array() && !its.empty() ? number_or(its.back(), "seconds", 0.0) : 0.0;
  e["seconds"] = {
      {"body", number_or(seconds, "body", 0.0)},
      {"layout", number_or(seconds, "garment", 0.0) + number_or(seconds, "limit surface", 0.0)},
      {"initial_solve", first},
      {"iterations", last - first},
      {"total", number_or(seconds, "total_this_run", 0.0)}};
  const nlohmann::json fit = member(result, "fit");
  for (const char* key :
       {"stretch_max", "stretch_min", "pressure_mmhg", "pressure_spread", "lift_off_share"})
    e[key] = member(fit, key);
  e["pieces"] = nlohmann::json::array();
  for (const auto& piece : member(fit, "pieces"))
    e["pieces"].push_back(
        {{"name", member(piece, "name")}, {"pressure_mmhg", member(piece, "pressure_mmhg")}});
  // The measured levels of the ease table (garment/ease_table.hpp): girths and ease.
  e["measurements"] = nlohmann::json::array();
  for (const auto& level : member(result, "measurements"))
    if (level.is_object() && level.value("status", std::string()) == "measured")
      e["measurements"].push_back(
          {{"name", member(level, "name")},
           {"body_circumference_m", member(level, "body_circumference_m")},
           {"pattern_circumference_m", member(level, "pattern_circumference_m")},
           {"ease_percent", member(level, "ease_percent")}});
  e["seams_mm"] = nlohmann::json::object();
  for (const auto& seam : member(pieces, "seams"))
    if (seam.contains("name") && seam["name"].is_string())
      e["seams_mm"][seam["name"].get<std::string>()] = {{"a", member(seam, "length_a_mm")},
                                                        {"b", member(seam, "length_b_mm")},
                                                        {"mismatch", member(seam, "mismatch_mm")}};
}

}  // namespace

fs::path grade_body_folder(const fs::path& dir, const std::string& name) {
  return dir / "bodies" / name;
}

GradeSummary gather_grade(const std::vector<GradeBody>& bodies, const fs::path& dir,
                          const std::string& design_file, const std::string& bodies_file) {
  GradeSummary summary;
  int done = 0, failed = 0, not_run = 0;
  for (const GradeBody& b : bodies) {
    GradedBody body;
    body.name = b.name;
    const fs::path folder = grade_body_folder(dir, b.name);
    const std::optional<GradeBodyStatus> status = read_grade_body_status(folder / kGradeBodyFile);
    body.status = status ? status->status : "not_run";
    body.error = status ? status->error : "";
    if (body.status == "done") {
      try {
        read_done_body(body, folder);
      } catch (const InputError& e) {
        body.status = "failed";
        body.error = std::string("its results cannot be read: ") + e.what();
        body.entry = nlohmann::json::object();
        body.pattern.reset();
      }
    }
    body.entry["name"] = body.name;
    body.entry["status"] = body.status;
    body.entry["folder"] = (fs::path("bodies") / b.name).string();
    if (!body.error.empty()) body.entry["error"] = body.error;
    done += body.status == "done";
    failed += body.status == "failed";
    not_run += body.status == "not_run" || body.status == "running";
    summary.bodies.push_back(std::move(body));
  }
  summary.not_done = failed + not_run;

  nlohmann::json seams = nlohmann::json::array();
  std::vector<std::string> names;  // seam names in the first done body's pattern order
  for (const GradedBody& body : summary.bodies)
    if (body.status == "done" && names.empty())
      for (const Seam& seam : body.pattern->seams) names.push_back(seam.name);
  for (const std::string& name : names) {
    nlohmann::json lengths = nlohmann::json::object(), changes = nlohmann::json::object();
    std::optional<double> previous;
    for (const GradedBody& body : summary.bodies) {
      if (body.status != "done" || !body.entry["seams_mm"].contains(name)) continue;
      const nlohmann::json& s = body.entry["seams_mm"][name];
      const double length = 0.5 * (number_or(s, "a", 0.0) + number_or(s, "b", 0.0));
      lengths[body.name] = length;
      if (previous) changes[body.name] = length - *previous;
      previous = length;
    }
    seams.push_back({{"name", name}, {"length_mm", lengths}, {"change_mm", changes}});
  }

  nlohmann::json entries = nlohmann::json::array();
  for (const GradedBody& body : summary.bodies) entries.push_back(body.entry);
  summary.json = {
      {"format", "tightfit-grade"},
      {"version", 1},
      {"design", design_file},
      {"bodies_file", bodies_file},
      {"date", utc_timestamp()},
      {"counts",
       {{"bodies", bodies.size()}, {"done", done}, {"failed", failed}, {"not_run", not_run}}},
      {"bodies", entries},
      {"seams", seams}};
  return summary;
}

}  // namespace tightfit
