#include "tightfit/patterns/text.hpp"

#include <cstdio>

namespace tightfit {

std::string unique_identifier(const std::string& name, std::set<std::string>& taken,
                              bool allow_dot) {
  std::string base;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || (allow_dot && c == '.');
    base.push_back(ok ? c : '_');
  }
  if (base.empty()) base.push_back('_');
  std::string id = base;
  for (int k = 2; taken.count(id); ++k) id = base + "_" + std::to_string(k);
  taken.insert(id);
  return id;
}

std::string ascii_escape(const std::string& text) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      out.push_back((c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?');
      ++i;
      continue;
    }
    int extra = c >= 0xf0 ? 3 : c >= 0xe0 ? 2 : c >= 0xc0 ? 1 : -1;
    unsigned code = extra == 3 ? c & 0x07u : extra == 2 ? c & 0x0fu : c & 0x1fu;
    bool valid = extra > 0;
    for (int k = 1; valid && k <= extra; ++k) {
      if (i + static_cast<size_t>(k) >= text.size()) {
        valid = false;
        break;
      }
      const auto cont = static_cast<unsigned char>(text[i + static_cast<size_t>(k)]);
      if ((cont & 0xc0u) != 0x80u) valid = false;
      code = (code << 6) | (cont & 0x3fu);
    }
    if (!valid) {
      out.push_back('?');
      ++i;
      continue;
    }
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "\\U+%04X", code);
    out += buffer;
    i += static_cast<size_t>(extra) + 1;
  }
  return out;
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string s(buffer);
  // "-0.000" → "0.000"
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace tightfit
