#include "tightfit/report/encoding.hpp"

#include <bit>
#include <stdexcept>

#include "tightfit/common/finite_output.hpp"

namespace tightfit {

namespace {

void append_le32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}

void replace_all(std::string& text, std::string_view from, std::string_view to) {
  std::size_t pos = 0;
  while ((pos = text.find(from, pos)) != std::string::npos) {
    text.replace(pos, from.size(), to);
    pos += to.size();
  }
}

}  // namespace

std::string base64_encode(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v =
        (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16) |
        (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8) |
        static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 2]));
    out.push_back(kAlphabet[(v >> 18) & 63u]);
    out.push_back(kAlphabet[(v >> 12) & 63u]);
    out.push_back(kAlphabet[(v >> 6) & 63u]);
    out.push_back(kAlphabet[v & 63u]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (rest == 2) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    out.push_back(kAlphabet[(v >> 18) & 63u]);
    out.push_back(kAlphabet[(v >> 12) & 63u]);
    out.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63u] : '=');
    out.push_back('=');
  }
  return out;
}

std::string base64_float32(const std::vector<double>& values) {
  require_finite_values(values.data(), values.size(), "a float32 array of the report data");
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const double v : values)
    append_le32(bytes, std::bit_cast<std::uint32_t>(static_cast<float>(v)));
  return base64_encode(bytes);
}

std::string base64_uint32(const std::vector<std::int64_t>& values) {
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const auto v : values) {
    if (v < 0 || v > 0xFFFFFFFFll) throw std::invalid_argument("base64_uint32: value out of range");
    append_le32(bytes, static_cast<std::uint32_t>(v));
  }
  return base64_encode(bytes);
}

std::string json_for_script(const nlohmann::json& json) {
  require_finite_json(json);
  std::string text = json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  // '<' only occurs inside JSON strings, where the escape u+003C is the same character.
  replace_all(text, "<", "\\u003c");
  return text;
}

}  // namespace tightfit
