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

/// Registers a command at static-initialization time.
struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup) {
    command_registry().push_back({std::move(name), std::move(setup)});
  }
};

}  // namespace tightfit::app
