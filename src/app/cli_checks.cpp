#include "cli_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tightfit/common/nearest_word.hpp"

namespace tightfit::app {
namespace {

CLI::Validator number_check(bool allow_zero) {
  const std::string rule = allow_zero ? ">= 0" : "> 0";
  return CLI::Validator(
      [allow_zero, rule](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < 0.0 ||
            (!allow_zero && v == 0.0))
          return "must be a number " + rule + ", got " + text;
        return {};
      },
      "NUMBER" + rule);
}

/// The long option names ("--out") of `app`.
std::vector<std::string> long_options(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
  return names;
}

}  // namespace

CLI::Validator positive_number() { return number_check(false); }
CLI::Validator non_negative_number() { return number_check(true); }

std::string parse_error_message(const CLI::App& root, const CLI::ParseError& e,
                                const std::vector<std::string>& args) {
  std::string message = e.what();
  std::vector<std::string> commands;
  for (const CLI::App* sub : root.get_subcommands([](const CLI::App*) { return true; }))
    commands.push_back(sub->get_name());
  const CLI::App* command = nullptr;
  for (const CLI::App* sub : root.get_subcommands()) command = sub;  // the parsed one
  if (!command) {
    // No command was recognized: the first word that is not an option is the typo.
    for (size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--threads") {
        ++i;
        continue;
      }
      if (args[i].starts_with("-")) continue;
      const std::string near = nearest_word(args[i], commands);
      message = "unknown command '" + args[i] + "'" +
                (near.empty() ? "" : "; did you mean '" + near + "'?") + " (commands: " +
                [&] {
                  std::string list;
                  for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
                  return list;
                }() +
                ")";
      return message;
    }
    return message;
  }
  std::vector<std::string> options = long_options(*command);
  for (const std::string& n : long_options(root)) options.push_back(n);
  std::string unknown;
  for (const std::string& a : args) {
    if (!a.starts_with("--")) continue;
    const std::string name = a.substr(0, a.find('='));
    if (std::find(options.begin(), options.end(), name) != options.end()) continue;
    // An option of other commands: say whose (the commonest mix-up, e.g.
    // `simulate --max-iterations`, an option of optimize).
    std::string owners;
    for (const CLI::App* sub : root.get_subcommands([](const CLI::App*) { return true; })) {
      const std::vector<std::string> theirs = long_options(*sub);
      if (sub != command && std::find(theirs.begin(), theirs.end(), name) != theirs.end())
        owners += (owners.empty() ? "" : ", ") + sub->get_name();
    }
    const std::string near = nearest_word(name, options);
    unknown += std::string(unknown.empty() ? "" : "\n") + "'" + command->get_name() +
               "' has no option '" + name + "'" +
               (!owners.empty() ? " (it is an option of " + owners + ")"
                                : (near.empty() ? "" : "; did you mean '" + near + "'?"));
  }
  return unknown.empty() ? message : unknown;
}

}  // namespace tightfit::app
