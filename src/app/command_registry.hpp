#pragma once
/// Each CLI command lives in its own file under commands/ and registers itself
/// here with a static `CommandRegistration`, so adding a command touches one file.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
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

/// What `tightfit COMMAND --help` shows around the options: the description (one
/// paragraph) and the footer (the examples).
struct CommandHelp {
  std::string name;
  std::string description;
  std::string examples;
};

/// A command's subcommand and its options (they live as long as the program).
template <class Options>
struct CommandOptions {
  CLI::App& cmd;
  Options& options;
};

/// Adds the subcommand of `help` to `root` with a default-made `Options`, which the
/// caller binds the command's options to; `run(options)` (or `run(options, cmd)` for a
/// command that asks which options were given) is its callback.
template <class Options, class Run>
CommandOptions<Options> add_command(CLI::App& root, const CommandHelp& help, Run run) {
  CLI::App* cmd = root.add_subcommand(help.name, help.description);
  cmd->footer(help.examples);
  auto options = std::make_shared<Options>();
  cmd->callback([options, cmd, run = std::move(run)] {
    if constexpr (std::is_invocable_v<Run, const Options&, const CLI::App&>)
      run(*options, *cmd);
    else
      run(*options);
  });
  return {*cmd, *options};
}

/// --out DIR (required) with `out_help` and --force, bound to `out` and `force`.
inline void add_output_options(CLI::App& cmd, std::string& out, bool& force,
                               const std::string& out_help = kOutHelp) {
  cmd.add_option("--out", out, out_help)->required();
  cmd.add_flag("--force", force, kForceHelp);
}

/// The options of a command that reads a scene and writes an output folder.
struct SceneRunOptions {
  std::string scene;
  std::string out;
  bool force = false;
};

/// SCENE (required), --out DIR and --force, bound to `o`.
inline void add_scene_run_options(CLI::App& cmd, SceneRunOptions& o) {
  cmd.add_option("scene", o.scene, "Scene file (JSON; schema: schema/scene.schema.json)")
      ->required();
  add_output_options(cmd, o.out, o.force);
}

/// Registers a command at static-initialization time.
struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup) {
    command_registry().push_back({std::move(name), std::move(setup)});
  }
};

}  // namespace tightfit::app
