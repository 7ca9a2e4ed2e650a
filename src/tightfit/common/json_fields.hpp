#pragma once
/// Strict reading of JSON objects for scene and spec files: every key must be known,
/// every value of the expected type; errors name the file and the JSON path
/// (e.g. "scene.json: /body/edge_length: expected a number, got string").
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// Reads the fields of one JSON object. Call the getters for every field you accept,
/// then `finish()`, which rejects keys that were never asked for.
class JsonFields {
 public:
  /// `source` is the file name for error messages, `path` the JSON pointer of `object`.
  JsonFields(const nlohmann::json& object, std::string source, std::string path);

  const std::string& source() const { return source_; }
  const std::string& path() const { return path_; }
  /// JSON pointer of a member, e.g. "/body/edge_length".
  std::string child_path(const std::string& key) const;
  bool has(const std::string& key);

  /// A finite number of magnitude ≤ kMaxJsonMagnitude. An explicit null is an error for
  /// every getter (never the default).
  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  /// A number that must be > 0 (or ≥ 0 when `allow_zero`).
  double positive(const std::string& key, std::optional<double> fallback = {},
                  bool allow_zero = false);
  /// An integer in the range of int (a larger one is an error saying so).
  int integer(const std::string& key, std::optional<int> fallback = {});
  bool boolean(const std::string& key, std::optional<bool> fallback = {});
  std::string string(const std::string& key, std::optional<std::string> fallback = {});
  /// A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     std::optional<std::string> fallback = {});
  Vec3 vec3(const std::string& key, std::optional<Vec3> fallback = {});
  Vec2 vec2(const std::string& key, std::optional<Vec2> fallback = {});
  /// A nested object (error if missing and `required`); nullopt when absent.
  std::optional<JsonFields> object(const std::string& key, bool required = false);
  /// An array of objects; more than `max_count` of them is an error saying so.
  std::vector<JsonFields> objects(const std::string& key, bool required = false,
                                  std::size_t max_count = std::numeric_limits<std::size_t>::max());
  /// The raw member (marks it as known); null json if absent.
  const nlohmann::json& raw(const std::string& key);

  /// `value` of member `key` when ≤ `max`; otherwise an InputError at its path saying
  /// "is V, more than MAX (WHY)".
  double at_most(const std::string& key, double value, double max, const std::string& why) const;

  /// Throws InputError naming the first unknown key.
  void finish() const;
  /// Throws InputError at this object's path (or a member's path when `key` given).
  [[noreturn]] void fail(const std::string& what, const std::string& key = "") const;

 private:
  const nlohmann::json& get(const std::string& key, const char* expected, bool required);

  const nlohmann::json* object_;
  std::string source_;
  std::string path_;
  std::set<std::string> known_;
};

/// The largest magnitude of a number read by JsonFields: far beyond any physical quantity
/// of a garment scene in SI units, far below where squares and sums overflow.
inline constexpr double kMaxJsonMagnitude = 1e15;

/// The most planes, panels, openings, pins or regions one scene section may list: more
/// than any body has parts, few enough that checking each against the rest stays quick.
inline constexpr std::size_t kMaxSceneParts = 256;

/// The largest coordinate (m) a state or checkpoint may hold: 10 km from the origin.
inline constexpr double kMaxCoordinate = 1e4;

/// `v` in the shortest form of 6 significant digits ("1e+308", "0.25").
std::string format_number(double v);

/// Deepest nesting of arrays and objects a JSON document may have (scenes, states and
/// checkpoints need fewer than 12).
inline constexpr int kMaxJsonDepth = 256;

/// Parses JSON text; InputError (source `source`) for a syntax error (with line and
/// column), nesting deeper than kMaxJsonDepth, or a key repeated in one object (naming
/// the key and both lines), checked before parsing.
nlohmann::json parse_json_text(const std::string& text, const std::string& source);

/// Reads a JSON file; InputError names the file (and line/column on a syntax error).
nlohmann::json read_json_file(const std::string& file);

}  // namespace tightfit
