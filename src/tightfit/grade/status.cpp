#include "tightfit/grade/status.hpp"

#include <set>

#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/version.hpp"

namespace tightfit {

void write_grade_body_status(const std::filesystem::path& file, const GradeBodyStatus& status) {
  nlohmann::json j = {{"format", "tightfit-grade-body"},
                      {"version", 1},
                      {"name", status.name},
                      {"status", status.status},
                      {"fingerprint", status.fingerprint},
                      {"seconds", status.seconds},
                      {"date", utc_timestamp()}};
  if (!status.error.empty()) j["error"] = status.error;
  write_json_atomically(file, j, 2);
}

std::optional<GradeBodyStatus> read_grade_body_status(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  nlohmann::json j;
  try {
    j = read_json_file(file.string());
  } catch (const InputError&) {
    return std::nullopt;
  }
  static const std::set<std::string> states = {"running", "done", "failed"};
  if (!j.is_object() || j.value("format", std::string()) != "tightfit-grade-body" ||
      !j.contains("status") || !j["status"].is_string() ||
      !states.contains(j["status"].get<std::string>()))
    return std::nullopt;
  GradeBodyStatus s;
  s.name = j.value("name", std::string());
  s.status = j["status"].get<std::string>();
  s.fingerprint = j.value("fingerprint", std::string());
  s.error = j.value("error", std::string());
  if (j.contains("seconds") && j["seconds"].is_number()) s.seconds = j["seconds"].get<double>();
  return s;
}

}  // namespace tightfit
