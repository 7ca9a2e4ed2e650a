#pragma once
/// The help text of every command, readable in an 80-column terminal: CLI11's layout
/// (option names in a 30-column left column, descriptions beside them) with every line
/// longer than 80 characters wrapped at word boundaries, continuation lines indented
/// to the description column; the root help lists each command by the first sentence
/// of its description.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace tightfit::app {

/// Lines of help text are at most this many characters (longer words stay whole).
inline constexpr std::size_t kHelpWidth = 80;

/// Wraps every line of `text` longer than `width` at spaces. A continuation line is
/// indented to `column` when the line has CLI11's two-column layout (text starting
/// at `column` after a gap of at least two spaces), else to the line's own
/// indentation. Lines that fit are left as they are.
std::string wrap_help_text(const std::string& text, std::size_t width, std::size_t column);

/// The first sentence of `description` (up to the first ". ", ";" or ":" outside
/// parentheses, or a line break), for the root help's list of commands.
std::string first_sentence(const std::string& description);

/// CLI11's formatter with wrap_help_text applied to the whole help, and the root's
/// command list shortened to first sentences.
class WrappingFormatter : public CLI::Formatter {
 public:
  std::string make_help(const CLI::App* app, std::string name,
                        CLI::AppFormatMode mode) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
};

}  // namespace tightfit::app
