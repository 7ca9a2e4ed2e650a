/// `tightfit version` (and `tightfit --version`, main.cpp): prints the program version
/// (common/version.hpp) and the linked library versions.
#include <Eigen/Core>
#include <cstdio>

#include "command_registry.hpp"
#include "tightfit/common/version.hpp"

namespace tightfit::app {
namespace {

const CommandRegistration kVersion{
    "version", [](CLI::App& root) {
      auto* cmd = root.add_subcommand("version", "Print the tightfit version and library versions");
      cmd->footer("Example:\n  tightfit version");
      cmd->callback([] {
        std::printf("tightfit %s (Eigen %d.%d.%d)\n", tightfit_version(), EIGEN_WORLD_VERSION,
                    EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
      });
    }};

}  // namespace
}  // namespace tightfit::app
