#pragma once
/// Text encodings used to build the self-contained report.html: base64 (for typed
/// arrays and data: URLs), HTML escaping, and JSON that is safe inside a <script>.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace tightfit {

/// Standard base64 (RFC 4648, with '=' padding) of `bytes`.
std::string base64_encode(std::string_view bytes);

/// Base64 of the values as little-endian float32 (what a JS Float32Array reads on every
/// platform that runs browsers). Values are rounded to float; a NaN or infinity throws
/// NonFiniteOutput (common/finite_output.hpp): no report carries one.
std::string base64_float32(const std::vector<double>& values);
/// Base64 of the values as little-endian uint32 (JS Uint32Array). Values must be >= 0.
std::string base64_uint32(const std::vector<std::int64_t>& values);

/// `json` serialized so that it can sit inside <script type="application/json">:
/// every '<' becomes the JSON escape of U+003C, so no "</script" or "<!--" can appear.
/// A NaN or infinity in `json` throws NonFiniteOutput (it would be written as null).
std::string json_for_script(const nlohmann::json& json);

}  // namespace tightfit
