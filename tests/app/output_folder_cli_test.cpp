/// The output-folder rule of every command (common/output_directory.hpp), end to end:
/// a user's files are never touched, `--out .` works, a file or an uncreatable folder is
/// an input error (exit 2).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit::output_folder_cli_test {

namespace fs = std::filesystem;
using test::CliRun;
using test::read_text;
using test::run_cli;

class OutputFolderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_output_folder_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A small sleeve on a rigid cylinder: simulate takes a fraction of a second.
    std::ofstream(dir_ / "scene.json") << R"({
      "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.02},
      "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                             "hoop_scale": 0.9, "edge_length": 0.02, "jitter": 0.0,
                             "pin_first_ring": true, "pin_last_ring": true}},
      "body_material": {"rigid": true}
    })";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string scene() const { return (dir_ / "scene.json").string(); }
  fs::path dir_;
};

TEST_F(OutputFolderCli, AUsersFolderIsRefusedAndWithForceKeepsItsFiles) {
  const fs::path mine = dir_ / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "my notes\n";
  CliRun r = run_cli("simulate " + scene() + " --out " + mine.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--force"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(mine / "notes.txt"), "my notes\n");
  EXPECT_FALSE(fs::exists(mine / "result.json"));
  r = run_cli("simulate " + scene() + " --out " + mine.string() + " --force");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(mine / "notes.txt"), "my notes\n");
  EXPECT_TRUE(fs::exists(mine / "result.json"));
  // Now a tightfit folder: a second run needs no --force and still keeps the notes.
  r = run_cli("simulate " + scene() + " --out " + mine.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(mine / "notes.txt"), "my notes\n");
  for (const auto& e : fs::directory_iterator(mine))
    EXPECT_EQ(e.path().filename().string().find(".tightfit-staging"), std::string::npos);
}

TEST_F(OutputFolderCli, EveryCommandFollowsTheRule) {
  const fs::path mine = dir_ / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "x\n";
  const CliRun run = run_cli("simulate " + scene() + " --out " + (dir_ / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> commands = {"layout " + scene(),
                                             "body --generator sphere --radius 0.1",
                                             "export " + (dir_ / "run").string()};
  for (const std::string& args : commands) {
    const CliRun r = run_cli(args + " --out " + mine.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("not written by tightfit"), std::string::npos) << args << r.output;
    EXPECT_EQ(read_text(mine / "notes.txt"), "x\n") << args;
  }
  nlohmann::json s = nlohmann::json::parse(read_text(dir_ / "scene.json"));
  s["optimize"] = {{"objectives", {{"stretch", {{"min", 1.02}, {"max", 1.06}}}}},
                   {"max_iterations", 1}};
  std::ofstream(dir_ / "opt.json") << s.dump();
  const CliRun r = run_cli("optimize " + (dir_ / "opt.json").string() + " --out " + mine.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(mine)) ++entries;
  EXPECT_EQ(entries, 1u);  // only the notes
}

TEST_F(OutputFolderCli, OutDotWorksAndAFileIsAnInputError) {
  const fs::path here = dir_ / "here";
  fs::create_directories(here);
  CliRun r = run_cli("simulate " + scene() + " --out .", here.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(here / "result.json"));
  EXPECT_TRUE(fs::exists(here / "state.json"));
  r = run_cli("simulate " + scene() + " --out " + (dir_ / "scene.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is a file"), std::string::npos) << r.output;
  r = run_cli("simulate " + scene() + " --out " + (dir_ / "scene.json" / "sub").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot create the output folder"), std::string::npos) << r.output;
}

TEST_F(OutputFolderCli, AFailedSolveKeepsItsLastStateWhereTheUserAsked) {
  // One Newton iteration is not enough: the solve fails (exit 3), --out is not created,
  // and --keep-failed holds the last state with the unbalanced force per vertex.
  nlohmann::json s = nlohmann::json::parse(read_text(dir_ / "scene.json"));
  s["solver"] = {{"max_iterations", 1}};
  std::ofstream(dir_ / "failing.json") << s.dump();
  const fs::path out = dir_ / "out", kept = dir_ / "failed";
  CliRun r = run_cli("simulate " + (dir_ / "failing.json").string() + " --out " + out.string() +
                     " --keep-failed " + kept.string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("  newton   1  force before "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("largest force "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("on garment vertex"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  for (const char* name : {"garment_residual.ply", "body_residual.ply", "report.html",
                           "result.json", "state.json", "garment.ply"})
    EXPECT_TRUE(fs::exists(kept / name)) << name;
  const nlohmann::json result = nlohmann::json::parse(read_text(kept / "result.json"));
  EXPECT_FALSE(result["newton"]["converged"].get<bool>());
  EXPECT_GT(result["newton"]["final_force_residual_n"].get<double>(),
            result["newton"]["force_tolerance_n"].get<double>());
  EXPECT_GT(result["failure"]["garment_residual_max_n"].get<double>(), 0.0);
  const std::string ply = read_text(kept / "garment_residual.ply");
  EXPECT_NE(ply.find("property double residual_n"), std::string::npos);
  EXPECT_NE(ply.find("property double residual_force_2"), std::string::npos);
  // The report colours the garment by the unbalanced force; the kept folder is a run
  // folder, and export regenerates the same report from its state.
  const std::string coloring = "Unbalanced force (the solve did not converge)";
  EXPECT_NE(read_text(kept / "report.html").find(coloring), std::string::npos);
  r = run_cli("export " + kept.string() + " --out " + (dir_ / "exported").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read_text(dir_ / "exported" / "report.html").find(coloring), std::string::npos);
  // --keep-failed must not be the output folder.
  r = run_cli("simulate " + (dir_ / "failing.json").string() + " --out " + out.string() +
              " --keep-failed " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--keep-failed"), std::string::npos) << r.output;
}

TEST_F(OutputFolderCli, AFullDiskIsAnInputErrorAndLeavesTheFolderAsItWas) {
  // A 96 kB file system: the report alone does not fit.
  const fs::path disk = dir_ / "disk";
  fs::create_directories(disk);
  if (std::system(("mount -t tmpfs -o size=96k tmpfs " + disk.string() + " 2>/dev/null").c_str()) !=
      0)
    GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  struct Unmount {
    fs::path path;
    ~Unmount() { (void)!std::system(("umount " + path.string()).c_str()); }
  } unmount{disk};
  fs::create_directories(disk / "mine");
  std::ofstream(disk / "mine" / "notes.txt") << "my notes\n";

  CliRun r = run_cli("simulate " + scene() + " --out " + (disk / "run").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(disk / "run"));
  // Into a folder of the user's (--force): their file stays, nothing else is left.
  r = run_cli("simulate " + scene() + " --out " + (disk / "mine").string() + " --force");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(disk / "mine")) names.push_back(e.path().filename());
  EXPECT_EQ(names, std::vector<std::string>{"notes.txt"});
  EXPECT_EQ(read_text(disk / "mine" / "notes.txt"), "my notes\n");
}

}  // namespace tightfit::output_folder_cli_test
