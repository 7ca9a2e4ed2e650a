/// `tightfit version`: prints the program version and the linked library versions.
#include <Eigen/Core>
#include <cstdio>

#include "command_registry.hpp"

namespace tightfit::app {
namespace {

const CommandRegistration kVersion{"version", [](CLI::App& root) {
  auto* cmd = root.add_subcommand("version", "Print the tightfit version and library versions");
  cmd->callback([] {
    std::printf("tightfit 0.1.0 (Eigen %d.%d.%d)\n", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                EIGEN_MINOR_VERSION);
  });
}};

}  // namespace
}  // namespace tightfit::app
