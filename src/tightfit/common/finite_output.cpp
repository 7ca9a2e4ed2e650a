#include "tightfit/common/finite_output.hpp"

#include <ostream>

#include "tightfit/common/atomic_file.hpp"

namespace tightfit {

namespace {

/// JSON pointer escaping of one object key (RFC 6901: ~ → ~0, / → ~1).
std::string pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

void check_json(const nlohmann::json& json, std::string& path) {
  if (json.is_number_float()) {
    const double value = json.get<double>();
    if (!std::isfinite(value))
      throw NonFiniteOutput("non-finite number (" + non_finite_name(value) + ") at " +
                            (path.empty() ? std::string("/") : path));
    return;
  }
  if (!json.is_structured()) return;
  const std::size_t length = path.size();
  if (json.is_array()) {
    std::size_t k = 0;
    for (const nlohmann::json& item : json) {
      path.push_back('/');
      path.append(std::to_string(k++));
      check_json(item, path);
      path.resize(length);
    }
  } else {
    for (auto it = json.begin(); it != json.end(); ++it) {
      path.push_back('/');
      path.append(pointer_token(it.key()));
      check_json(it.value(), path);
      path.resize(length);
    }
  }
}

template <class T>
void check_values(const T* values, std::size_t count, std::string_view what) {
  for (std::size_t i = 0; i < count; ++i)
    if (!std::isfinite(values[i]))
      throw NonFiniteOutput("non-finite number (" +
                            non_finite_name(static_cast<double>(values[i])) + ") in " +
                            std::string(what) + ", element " + std::to_string(i));
}

}  // namespace

std::string non_finite_name(double value) {
  if (std::isnan(value)) return "nan";
  return value > 0.0 ? "inf" : "-inf";
}

void require_finite_json(const nlohmann::json& json) {
  std::string path;
  check_json(json, path);
}

void require_finite_values(const double* values, std::size_t count, std::string_view what) {
  check_values(values, count, what);
}

void require_finite_values(const float* values, std::size_t count, std::string_view what) {
  check_values(values, count, what);
}

void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& json,
                           int indent) {
  write_file_atomically(path, [&](std::ostream& out) {
    require_finite_json(json);
    out << json.dump(indent) << '\n';
  });
}

}  // namespace tightfit
