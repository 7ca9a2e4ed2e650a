/// The 12-piece wetsuit example laid out from the command line: the body cropped by
/// local planes anchored on the rig's skeleton, the layout's local cuffs, the pieces
/// flattened within the layout's tolerances.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit {
namespace wetsuit_cli_test {

namespace fs = std::filesystem;
using test::run_cli;

TEST(WetsuitCli, TheTwelvePieceWetsuitLaysOutOnTheCroppedRegularBody) {
  const fs::path out =
      fs::temp_directory_path() / ("tightfit_wetsuit_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = run_cli("layout " + std::string(TIGHTFIT_SOURCE_DIR) +
                         "/examples/optimize_wetsuit_regular.json --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "pieces.json");
  const nlohmann::json pieces = nlohmann::json::parse(in);
  ASSERT_EQ(pieces["pieces"].size(), 12u);
  std::ifstream layout_in(out / "layout.json");
  const nlohmann::json layout = nlohmann::json::parse(layout_in);
  for (const auto& piece : layout["build"]["pieces"]) {
    SCOPED_TRACE(piece["name"].get<std::string>());
    EXPECT_EQ(piece["flattening"]["flipped_triangles"].get<int>(), 0);
    EXPECT_LT(piece["flattening"]["area_error"].get<double>(), 0.05);
  }
  fs::remove_all(out);
}

}  // namespace wetsuit_cli_test
}  // namespace tightfit
