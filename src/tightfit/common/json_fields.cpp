#include "tightfit/common/json_fields.hpp"

#include "tightfit/common/json_key_observer.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

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
  return *it;
}

double JsonFields::number(const std::string& key) {
  const auto& j = get(key, "a number", true);
  if (!j.is_number()) fail("expected a number, got " + type_name(j), key);
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail("expected a finite number", key);
  return v;
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

std::vector<JsonFields> JsonFields::objects(const std::string& key, bool required) {
  const auto& j = get(key, "an array of objects", required);
  std::vector<JsonFields> out;
  if (j.is_null()) return out;
  if (!j.is_array()) fail("expected an array of objects, got " + type_name(j), key);
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string p = child_path(key) + "/" + std::to_string(i);
    if (!j[i].is_object())
      throw InputError(source_, p + ": expected an object, got " + type_name(j[i]));
    out.emplace_back(j[i], source_, p);
  }
  return out;
}

const nlohmann::json& JsonFields::raw(const std::string& key) { return get(key, "", false); }

void JsonFields::finish() const {
  for (auto it = object_->begin(); it != object_->end(); ++it)
    if (!known_.count(it.key())) fail("unknown key \"" + it.key() + "\"", it.key());
}

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  // Nesting depth outside strings: nlohmann's copy and dump recurse once per level, so a
  // file of a million brackets would overflow the stack later, far from the parser.
  int depth = 0;
  bool in_string = false, escaped = false;
  std::size_t line = 1;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(source, "invalid JSON: nested deeper than " +
                                     std::to_string(kMaxJsonDepth) + " levels (line " +
                                     std::to_string(line) + ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source, std::string("invalid JSON: ") + e.what());
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond the double range (1e400): found by fuzzing, it escaped as a
    // non-input error.
    throw InputError(source, std::string("invalid JSON (a number out of range): ") + e.what());
  }
}

nlohmann::json read_json_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(file, "cannot read file");
  return parse_json_text(text.str(), file);
}

}  // namespace tightfit
