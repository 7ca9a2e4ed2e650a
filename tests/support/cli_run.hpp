#pragma once
/// Runs the built `tightfit` binary (TIGHTFIT_CLI, a compile definition of every test
/// executable) and captures its exit code and output, for the command-line tests.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tightfit::test {

struct CliRun {
  int exit_code;       ///< the process exit code, -1 if it did not exit normally
  std::string output;  ///< stdout and stderr
};

/// Runs `tightfit ARGS` in folder `cwd` (the test's current folder if empty).
inline CliRun run_cli(const std::string& args, const std::string& cwd = "") {
  static int calls = 0;
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() /
      ("tightfit_cli_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".log");
  const std::string command = (cwd.empty() ? "" : "cd '" + cwd + "' && ") +
                              std::string(TIGHTFIT_CLI) + " " + args + " > " + log.string() +
                              " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

/// The whole content of a file (empty if it cannot be read).
inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace tightfit::test
