/// `tightfit help [COMMAND [SUBCOMMAND]]`: the help of tightfit or of one command, as
/// `tightfit --help` and `tightfit COMMAND --help` print it.
#include <cstdio>
#include <string>
#include <vector>

#include "command_registry.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/nearest_word.hpp"

namespace tightfit::app {
namespace {

void print_help(const CLI::App& root, const std::vector<std::string>& words) {
  const CLI::App* app = &root;
  std::string path = "tightfit";
  for (const std::string& word : words) {
    std::vector<std::string> names;
    const CLI::App* next = nullptr;
    for (const CLI::App* sub : app->get_subcommands([](const CLI::App*) { return true; })) {
      names.push_back(sub->get_name());
      if (sub->get_name() == word) next = sub;
    }
    if (!next) {
      const std::string near = nearest_word(word, names);
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      throw InputError("tightfit help", "'" + path + "' has no command '" + word + "'" +
                                            (near.empty() ? "" : "; did you mean '" + near + "'?") +
                                            (list.empty() ? "" : " (commands: " + list + ")"));
    }
    app = next;
    path += " " + word;
  }
  // The formatter directly: App::help() would show the help of the command being run
  // (this one).
  std::fputs(app->get_formatter()->make_help(app, path, CLI::AppFormatMode::Normal).c_str(),
             stdout);
}

const CommandRegistration kHelp{
    "help", [](CLI::App& root) {
      auto words = std::make_shared<std::vector<std::string>>();
      CLI::App* cmd = root.add_subcommand("help", "Print the help of tightfit or of a command");
      cmd->footer(
          "Examples:\n  tightfit help\n  tightfit help optimize\n  tightfit help fabric fit");
      cmd->add_option("command", *words, "The command (and subcommand) to explain");
      const CLI::App* top = &root;
      cmd->callback([top, words] { print_help(*top, *words); });
    }};

}  // namespace
}  // namespace tightfit::app
