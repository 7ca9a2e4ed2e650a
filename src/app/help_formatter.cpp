#include "help_formatter.hpp"

#include <sstream>

namespace tightfit::app {
namespace {

/// Where the description of a two-column line starts (`column`), or the line's own
/// indentation when it is not a two-column line.
std::size_t continuation_indent(const std::string& line, std::size_t column) {
  const std::size_t own = line.find_first_not_of(' ');
  if (own == std::string::npos) return 0;
  if (own < column && line.size() > column && line[column] != ' ' && line[column - 1] == ' ' &&
      line[column - 2] == ' ')
    return column;
  return own;
}

/// Appends `line` to `out`, wrapped to `width`.
void wrap_line(const std::string& line, std::size_t width, std::size_t column, std::string& out) {
  if (line.size() <= width) {
    out += line;
    return;
  }
  const std::size_t indent = continuation_indent(line, column);
  std::string rest = line;
  bool first = true;
  while (rest.size() > width) {
    const std::size_t start = first ? rest.find_first_not_of(' ') : indent;
    std::size_t cut = rest.rfind(' ', width);
    if (cut == std::string::npos || cut <= start) cut = rest.find(' ', width);  // a long word
    if (cut == std::string::npos) break;
    std::size_t end = cut;
    while (end > start && rest[end - 1] == ' ') --end;
    out += rest.substr(0, end);
    out += '\n';
    const std::size_t next = rest.find_first_not_of(' ', cut);
    if (next == std::string::npos) {
      rest.clear();
      break;
    }
    rest = std::string(indent, ' ') + rest.substr(next);
    first = false;
  }
  out += rest;
}

}  // namespace

std::string wrap_help_text(const std::string& text, std::size_t width, std::size_t column) {
  std::string out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = text.find('\n', begin);
    const std::string line =
        text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    wrap_line(line, width, column, out);
    if (end == std::string::npos) break;
    out += '\n';
    begin = end + 1;
  }
  return out;
}

std::string first_sentence(const std::string& description) {
  int depth = 0;
  for (std::size_t i = 0; i < description.size(); ++i) {
    const char c = description[i];
    if (c == '(') ++depth;
    if (c == ')' && depth > 0) --depth;
    if (c == '\n') return description.substr(0, i);
    if (depth > 0) continue;
    if (c == ';' || c == ':') return description.substr(0, i);
    if (c == '.' && (i + 1 == description.size() || description[i + 1] == ' '))
      return description.substr(0, i);
  }
  return description;
}

std::string WrappingFormatter::make_help(const CLI::App* app, std::string name,
                                         CLI::AppFormatMode mode) const {
  return wrap_help_text(CLI::Formatter::make_help(app, std::move(name), mode), kHelpWidth,
                        get_column_width());
}

std::string WrappingFormatter::make_subcommand(const CLI::App* sub) const {
  std::stringstream out;
  CLI::detail::format_help(out, sub->get_display_name(), first_sentence(sub->get_description()),
                           get_column_width());
  return out.str();
}

}  // namespace tightfit::app
