#pragma once
/// Small text helpers shared by the pattern writers.
#include <set>
#include <string>

#include "tightfit/common/xml_text.hpp"

namespace tightfit {

/// Replaces every character outside [A-Za-z0-9_-] (and '.' when `allow_dot`) by '_'
/// and appends "_2", "_3", ... when the result is already in `taken` (which it joins).
std::string unique_identifier(const std::string& name, std::set<std::string>& taken,
                              bool allow_dot = true);

/// 7-bit ASCII form of UTF-8 `text`: printable ASCII is kept, other code points become
/// "\U+XXXX" (as DXF readers understand), control characters and malformed bytes
/// become '?'.
std::string ascii_escape(const std::string& text);

/// A number in fixed notation with `decimals` digits (no exponent), "-0" printed as "0".
std::string fixed(double value, int decimals);

}  // namespace tightfit
