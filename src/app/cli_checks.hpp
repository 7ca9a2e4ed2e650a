#pragma once
/// Readable checks of option values and the suggestions of the error messages, for
/// every command (CLI11's own range checks print the type's whole range, e.g. a
/// 300-digit upper bound).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace tightfit::app {

/// A number > 0 ("--directions: must be a number > 0, got -3").
CLI::Validator positive_number();
/// A number >= 0.
CLI::Validator non_negative_number();

/// The message for a command-line error `e` of `root` with the arguments `args`: CLI11's
/// message, plus "did you mean …?" for a mistyped command or option.
std::string parse_error_message(const CLI::App& root, const CLI::ParseError& e,
                                const std::vector<std::string>& args);

}  // namespace tightfit::app
