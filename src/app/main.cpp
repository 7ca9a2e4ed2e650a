/// tightfit command-line interface: dispatches to the commands in commands/.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "cli_checks.hpp"
#include "command_registry.hpp"
#include "help_formatter.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/interrupt.hpp"
#include "tightfit/common/memory_reuse.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/version.hpp"

namespace tightfit::app {
std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> registry;
  return registry;
}
}  // namespace tightfit::app

int main(int argc, char** argv) {
  using namespace tightfit;
  keep_freed_memory_for_reuse();
  CLI::App root{
      "tightfit: physics-based pattern design for skintight garments "
      "(Montes et al., SIGGRAPH 2020).\nRun 'tightfit COMMAND --help' for a command's options."};
  root.formatter(std::make_shared<app::WrappingFormatter>());
  root.set_version_flag("--version", std::string("tightfit ") + tightfit_version());
  root.require_subcommand(1);
  root.fallthrough();  // --threads may also follow the command's name
  try {
    set_thread_count(default_thread_count());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  root.add_option_function<int>(
          "--threads", [](int n) { set_thread_count(n); },
          "Threads for the element loops and the BLAS (default: TIGHTFIT_THREADS, else the "
          "number of cores)")
      ->check(CLI::Range(1, 1024));
  auto& registry = app::command_registry();
  std::sort(registry.begin(), registry.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  for (const auto& entry : registry) entry.setup(root);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return root.exit(e);  // --help, --version
    // Every command-line mistake is bad input: exit 2, with a suggestion for a typo.
    std::fprintf(
        stderr, "error: %s\nRun 'tightfit --help' or 'tightfit COMMAND --help'.\n",
        app::parse_error_message(root, e, std::vector<std::string>(argv + 1, argv + argc)).c_str());
    return 2;
  } catch (const Interrupted& e) {
    return 128 + e.signal;
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const SolverError& e) {
    std::fprintf(stderr, "solver error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
