#pragma once
/// Small parsing helpers shared by the mesh readers and writers (internal to the
/// geometry layer, but usable elsewhere): whole-file reading, line iteration with
/// line numbers, tokenising and locale-independent number conversion.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tightfit::text {

/// The whole file as bytes. Throws InputError(path, ...) if it cannot be read.
std::string read_file(const std::filesystem::path& path);

/// Iterates over the lines of a text buffer; handles "\n" and "\r\n" endings.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t start = 0) : text_(text), pos_(start) {}
  /// The next line without its ending, or nullopt at the end of the buffer.
  std::optional<std::string_view> next();
  /// 1-based number of the line returned last (0 before the first call).
  int line_number() const { return line_; }
  /// Byte offset just after the line returned last.
  std::size_t position() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_;
  int line_ = 0;
};

/// Splits `line` at white space (space, tab, \n, \r, \v, \f) into `out` (cleared first).
void split(std::string_view line, std::vector<std::string_view>& out);
/// `line` without leading and trailing blanks.
std::string_view trim(std::string_view line);
/// `line` up to the first `comment` character.
std::string_view strip_comment(std::string_view line, char comment = '#');

/// The whole token as a double (accepts a leading '+', "inf", "nan"); nullopt otherwise.
std::optional<double> to_double(std::string_view token);
/// The whole token as a 64-bit integer (accepts a leading '+'); nullopt otherwise.
std::optional<std::int64_t> to_int(std::string_view token);

/// Shortest decimal text that reads back to exactly `value`.
std::string format_double(double value);

/// Lower-case extension of `path` including the dot, e.g. ".obj".
std::string lower_extension(const std::filesystem::path& path);

/// "line N: " prefix for reader error messages.
std::string at_line(int line);

}  // namespace tightfit::text
