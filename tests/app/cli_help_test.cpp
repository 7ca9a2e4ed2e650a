// The help of every command fits an 80-column terminal and ends with an example, and
// an optimize run's progress has a header and a terse mode.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_run.hpp"

namespace tightfit::cli_help_test {

using test::CliRun;
using test::run_cli;

/// Lines of `text` longer than `width` characters (UTF-8 code points).
std::vector<std::string> long_lines(const std::string& text, std::size_t width) {
  std::vector<std::string> found;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::size_t code_points = 0;
    for (const unsigned char c : line) code_points += (c & 0xC0) != 0x80;
    if (code_points > width) found.push_back(line);
  }
  return found;
}

TEST(CliHelp, EveryCommandsHelpFitsEightyColumnsAndShowsAnExample) {
  const CliRun root = run_cli("--help");
  ASSERT_EQ(root.exit_code, 0) << root.output;
  EXPECT_TRUE(long_lines(root.output, 80).empty()) << long_lines(root.output, 80).front();
  for (const std::string command : {"body", "check-gradient", "export", "grade", "layout",
                                    "optimize", "pose", "simulate", "version"}) {
    EXPECT_NE(root.output.find("  " + command + " "), std::string::npos) << command;
    const CliRun help = run_cli(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << "\n" << help.output;
    const std::vector<std::string> wide = long_lines(help.output, 80);
    EXPECT_TRUE(wide.empty()) << command << ": " << (wide.empty() ? "" : wide.front());
    EXPECT_NE(help.output.find("Example"), std::string::npos) << command;
    EXPECT_NE(help.output.find("\n  tightfit " + command), std::string::npos) << command;
  }
}

TEST(CliHelp, OptimizeProgressHasAHeaderAndATerseMode) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("tightfit_cli_help_" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  const std::string scene =
      std::string(TIGHTFIT_SOURCE_DIR) + "/examples/optimize_sleeve_stretch.json";
  std::string args = "optimize " + scene;
  args += " --max-iterations 1 --out ";
  args += out.string();
  const CliRun full = run_cli(args);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  const std::size_t header = full.output.find("elapsed  left");
  ASSERT_NE(header, std::string::npos) << full.output;
  EXPECT_LT(header, full.output.find("0/1 ")) << full.output;
  EXPECT_NE(full.output.find("1/1 "), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("stretch ", header), std::string::npos) << "the terms line\n"
                                                                     << full.output;
  EXPECT_TRUE(long_lines(full.output.substr(header), 100).empty()) << full.output;

  args += " --terse";
  const CliRun terse = run_cli(args);
  ASSERT_EQ(terse.exit_code, 0) << terse.output;
  const std::size_t terse_header = terse.output.find("elapsed  left");
  ASSERT_NE(terse_header, std::string::npos) << terse.output;
  EXPECT_NE(terse.output.find("1/1 "), std::string::npos) << terse.output;
  EXPECT_EQ(terse.output.find("stretch ", terse_header), std::string::npos) << "no terms line\n"
                                                                            << terse.output;
  std::filesystem::remove_all(out);
}

}  // namespace tightfit::cli_help_test
