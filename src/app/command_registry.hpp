#pragma once
/// Each CLI command lives in its own file under commands/ and registers itself
/// here with a static `CommandRegistration`, so adding a command touches one file.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace tightfit::app {

/// Adds the command's subcommand (options and callback) to the root app.
using CommandSetup = std::function<void(CLI::App& root)>;

struct CommandEntry {
  std::string name;
  CommandSetup setup;
};

/// All registered commands, in name order once the program starts.
std::vector<CommandEntry>& command_registry();

/// Help of every command's --out and --force (the rule: common/output_directory.hpp).
inline constexpr const char* kOutHelp =
    "Output folder: missing, empty or an earlier tightfit output folder (tightfit replaces "
    "its own files there and deletes nothing else; a failed run leaves it as it was)";
inline constexpr const char* kForceHelp =
    "Write into a non-empty folder that tightfit did not make (only tightfit's own files "
    "are written; nothing is deleted)";

/// Registers a command at static-initialization time.
struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup) {
    command_registry().push_back({std::move(name), std::move(setup)});
  }
};

}  // namespace tightfit::app
