#include "tightfit/common/json_fields.hpp"

#include "tightfit/common/json_key_observer.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "tightfit/common/input_file.hpp"

namespace tightfit {
namespace {

std::string type_name(const nlohmann::json& j) { return j.type_name(); }

thread_local JsonKeyObserver key_observer;

/// Marks `key` as known and reports it to the thread's observer, if any.
void ask(std::set<std::string>& known, const std::string& source, const std::string& path,
         const std::string& key) {
  known.insert(key);
  if (key_observer) key_observer(source, path, key);
}

}  // namespace

ScopedJsonKeyObserver::ScopedJsonKeyObserver(JsonKeyObserver observer)
    : previous_(std::exchange(key_observer, std::move(observer))) {}

ScopedJsonKeyObserver::~ScopedJsonKeyObserver() { key_observer = std::move(previous_); }

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

JsonFields::JsonFields(const nlohmann::json& object, std::string source, std::string path)
    : object_(&object), source_(std::move(source)), path_(std::move(path)) {
  if (!object.is_object())
    throw InputError(
        source_, (path_.empty() ? "/" : path_) + ": expected an object, got " + type_name(object));
}

std::string JsonFields::child_path(const std::string& key) const { return path_ + "/" + key; }

bool JsonFields::has(const std::string& key) {
  ask(known_, source_, path_, key);
  return object_->contains(key);
}

void JsonFields::fail(const std::string& what, const std::string& key) const {
  const std::string where = key.empty() ? (path_.empty() ? "/" : path_) : child_path(key);
  throw InputError(source_, where + ": " + what);
}

const nlohmann::json& JsonFields::get(const std::string& key, const char* expected, bool required) {
  ask(known_, source_, path_, key);
  static const nlohmann::json null_json;
  auto it = object_->find(key);
  if (it == object_->end()) {
    if (required) fail(std::string("missing (expected ") + expected + ")", key);
    return null_json;
  }
  // An explicit null is never taken for "absent": it is a mistake or a placeholder.
  if (it->is_null())
    fail(std::string("is null (expected ") + expected +
             (required ? ")" : "; leave the key out for the default)"),
         key);
  return *it;
}

double JsonFields::number(const std::string& key) {
  const auto& j = get(key, "a number", true);
  if (!j.is_number()) fail("expected a number, got " + type_name(j), key);
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail("expected a finite number", key);
  if (std::abs(v) > kMaxJsonMagnitude)
    fail("is " + format_number(v) + ", beyond ±" + format_number(kMaxJsonMagnitude) +
             " (no quantity of a scene in SI units is that large)",
         key);
  return v;
}

double JsonFields::at_most(const std::string& key, double value, double max,
                           const std::string& why) const {
  if (value > max)
    fail("is " + format_number(value) + ", more than " + format_number(max) + " (" + why + ")",
         key);
  return value;
}

double JsonFields::number(const std::string& key, double fallback) {
  if (!has(key)) return fallback;
  return number(key);
}

double JsonFields::positive(const std::string& key, std::optional<double> fallback,
                            bool allow_zero) {
  if (!has(key)) {
    if (fallback) return *fallback;
    fail("missing (expected a positive number)", key);
  }
  const double v = number(key);
  if (allow_zero ? v < 0.0 : v <= 0.0)
    fail(std::string("expected a ") + (allow_zero ? "non-negative" : "positive") + " number, got " +
             std::to_string(v),
         key);
  return v;
}

int JsonFields::integer(const std::string& key, std::optional<int> fallback) {
  const auto& j = get(key, "an integer", !fallback);
  if (j.is_null()) return *fallback;
  if (!j.is_number_integer()) fail("expected an integer, got " + type_name(j), key);
  const bool too_large = j.is_number_unsigned()
                             ? j.get<std::uint64_t>() > std::numeric_limits<int>::max()
                             : j.get<std::int64_t>() > std::numeric_limits<int>::max();
  if (too_large || j.get<std::int64_t>() < std::numeric_limits<int>::min())
    fail("is " + j.dump() + ", out of range (an integer from " +
             std::to_string(std::numeric_limits<int>::min()) + " to " +
             std::to_string(std::numeric_limits<int>::max()) + ")",
         key);
  return j.get<int>();
}

bool JsonFields::boolean(const std::string& key, std::optional<bool> fallback) {
  const auto& j = get(key, "true or false", !fallback);
  if (j.is_null()) return *fallback;
  if (!j.is_boolean()) fail("expected true or false, got " + type_name(j), key);
  return j.get<bool>();
}

std::string JsonFields::string(const std::string& key, std::optional<std::string> fallback) {
  const auto& j = get(key, "a string", !fallback);
  if (j.is_null()) return *fallback;
  if (!j.is_string()) fail("expected a string, got " + type_name(j), key);
  return j.get<std::string>();
}

std::string JsonFields::choice(const std::string& key, const std::vector<std::string>& choices,
                               std::optional<std::string> fallback) {
  const std::string v = string(key, fallback);
  for (const auto& c : choices)
    if (c == v) return v;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail("unknown value \"" + v + "\" (expected one of: " + list + ")", key);
}

namespace {
template <int N>
Eigen::Matrix<double, N, 1> read_vector(JsonFields& f, const nlohmann::json& j,
                                        const std::string& key) {
  if (!j.is_array() || j.size() != N)
    f.fail("expected an array of " + std::to_string(N) + " numbers", key);
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) {
    if (!j[i].is_number()) f.fail("expected an array of " + std::to_string(N) + " numbers", key);
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) f.fail("expected finite numbers", key);
    if (std::abs(v[i]) > kMaxJsonMagnitude)
      f.fail("holds " + format_number(v[i]) + ", beyond ±" + format_number(kMaxJsonMagnitude), key);
  }
  return v;
}
}  // namespace

Vec3 JsonFields::vec3(const std::string& key, std::optional<Vec3> fallback) {
  const auto& j = get(key, "an array of 3 numbers", !fallback);
  if (j.is_null()) return *fallback;
  return read_vector<3>(*this, j, key);
}

Vec2 JsonFields::vec2(const std::string& key, std::optional<Vec2> fallback) {
  const auto& j = get(key, "an array of 2 numbers", !fallback);
  if (j.is_null()) return *fallback;
  return read_vector<2>(*this, j, key);
}

std::optional<JsonFields> JsonFields::object(const std::string& key, bool required) {
  const auto& j = get(key, "an object", required);
  if (j.is_null()) return std::nullopt;
  if (!j.is_object()) fail("expected an object, got " + type_name(j), key);
  return JsonFields(j, source_, child_path(key));
}

std::vector<JsonFields> JsonFields::objects(const std::string& key, bool required,
                                            std::size_t max_count) {
  const auto& j = get(key, "an array of objects", required);
  std::vector<JsonFields> out;
  if (j.is_null()) return out;
  if (!j.is_array()) fail("expected an array of objects, got " + type_name(j), key);
  if (j.size() > max_count)
    fail("lists " + std::to_string(j.size()) + " entries, more than " + std::to_string(max_count) +
             " (more than any body or garment has parts)",
         key);
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string p = child_path(key) + "/" + std::to_string(i);
    if (!j[i].is_object())
      throw InputError(source_, p + ": expected an object, got " + type_name(j[i]));
    out.emplace_back(j[i], source_, p);
  }
  return out;
}

const nlohmann::json& JsonFields::raw(const std::string& key) {
  ask(known_, source_, path_, key);
  static const nlohmann::json null_json;
  const auto it = object_->find(key);
  return it == object_->end() ? null_json : *it;
}

void JsonFields::finish() const {
  for (auto it = object_->begin(); it != object_->end(); ++it)
    if (!known_.count(it.key())) fail("unknown key \"" + it.key() + "\"", it.key());
}

namespace {

/// The text of a JSON string literal's content `raw` (escapes decoded when it has any).
std::string decoded(const std::string& raw) {
  if (raw.find('\\') == std::string::npos) return raw;
  try {
    return nlohmann::json::parse("\"" + raw + "\"").get<std::string>();
  } catch (const nlohmann::json::exception&) {
    return raw;  // the parser reports the bad escape
  }
}

/// What the pre-pass of parse_json_text keeps per open array or object.
struct Frame {
  bool object = false;
  std::map<std::string, std::size_t> keys;  ///< key → line
};

/// Checks nesting depth and repeated keys before nlohmann parses `text` (which keeps the
/// last of repeated keys without a word, and recurses once per nesting level).
void check_json_structure(const std::string& text, const std::string& source) {
  std::vector<Frame> frames;
  bool in_string = false, escaped = false, pending_key = false;
  std::size_t line = 1, string_start = 0, string_line = 0;
  std::string last_string;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"') {
        in_string = false;
        last_string = text.substr(string_start, i - string_start);
        pending_key = !frames.empty() && frames.back().object;
      }
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    if (c == ':' && pending_key) {
      const std::string key = decoded(last_string);
      const auto [it, fresh] = frames.back().keys.emplace(key, string_line);
      if (!fresh)
        throw InputError(source,
                         "invalid JSON: key \"" + key + "\" given twice in one object (lines " +
                             std::to_string(it->second) + " and " + std::to_string(string_line) +
                             "): only one value can count; remove the other");
    }
    pending_key = false;
    if (c == '"') {
      in_string = true;
      string_start = i + 1;
      string_line = line;
    } else if (c == '[' || c == '{') {
      if (static_cast<int>(frames.size()) >= kMaxJsonDepth)
        throw InputError(source, "invalid JSON: nested deeper than " +
                                     std::to_string(kMaxJsonDepth) + " levels (line " +
                                     std::to_string(line) + ")");
      frames.push_back({c == '{', {}});
    } else if ((c == ']' || c == '}') && !frames.empty()) {
      frames.pop_back();
    }
  }
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  check_json_structure(text, source);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line L, column C: WHAT" becomes
    // "SOURCE:L:C: invalid JSON: WHAT", the place as editors and compilers write it.
    const std::string what = e.what();
    const std::size_t at = what.find("at line "), comma = what.find(", column ", at),
                      colon = what.find(": ", comma);
    if (at == std::string::npos || comma == std::string::npos || colon == std::string::npos)
      throw InputError(source, "invalid JSON: " + what.substr(what.find(']') + 2));
    throw InputError(source + ":" + what.substr(at + 8, comma - at - 8) + ":" +
                         what.substr(comma + 9, colon - comma - 9),
                     "invalid JSON: " + what.substr(colon + 2));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond the double range (1e400): found by fuzzing, it escaped as a
    // non-input error.
    throw InputError(source, std::string("invalid JSON (a number out of range): ") + e.what());
  }
}

nlohmann::json read_json_file(const std::string& file) {
  return parse_json_text(read_input_file(file), file);
}

}  // namespace tightfit
