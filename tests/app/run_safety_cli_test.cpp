/// The promises of docs/files.md end to end: a real command's commit killed at many
/// moments leaves the folder as it was or complete; one writer per folder; `--resume`
/// refuses a checkpoint of other inputs; the interrupt hint is a command that works;
/// inputs that are not regular files are refused at once.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit::run_safety_cli_test {

namespace fs = std::filesystem;
using test::CliRun;
using test::read_text;
using test::run_cli;

/// A small sleeve on a rigid cylinder: simulate takes a fraction of a second; with an
/// "optimize" section, a few iterations take a few seconds.
nlohmann::json sleeve_scene() {
  return nlohmann::json::parse(R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.02},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                           "hoop_scale": 0.9, "edge_length": 0.02, "jitter": 0.0,
                           "pin_first_ring": true, "pin_last_ring": true}},
    "body_material": {"rigid": true}
  })");
}

nlohmann::json optimize_scene(int max_iterations) {
  nlohmann::json s = sleeve_scene();
  s["optimize"] = {{"objectives", {{"stretch", {{"min", 1.02}, {"max", 1.06}}}}},
                   {"max_iterations", max_iterations},
                   {"checkpoint_every", 1}};
  return s;
}

class RunSafetyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_run_safety_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const nlohmann::json& j) {
    std::ofstream(dir_ / name) << j.dump(2);
    return dir_ / name;
  }
  /// Runs a bash script in the test folder; returns its exit status.
  int bash(const std::string& script) {
    std::ofstream(dir_ / "script.sh") << script << "\n";
    return std::system(("bash " + (dir_ / "script.sh").string()).c_str());
  }
  fs::path dir_;
};

ino_t inode(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 ? st.st_ino : 0;
}

std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(folder))
    out[e.path().filename().string()] = read_text(e.path());
  return out;
}

TEST_F(RunSafetyCli, ACommitKilledAtAnyStepLeavesTheFolderAsItWasOrComplete) {
  const fs::path scene = write("scene.json", sleeve_scene());
  const fs::path out = dir_ / "out";
  CliRun r = run_cli("simulate " + scene.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ofstream(out / "notes.txt") << "mine";
  for (int k = 0; k < 10; ++k) std::ofstream(out / ("photo" + std::to_string(k))) << k;
  const auto names = contents(out);
  int killed = 0;
  for (int k = 0; k < 8; ++k) {
    const ino_t folder_before = inode(out);
    const auto before = contents(out);
    ::setenv("TIGHTFIT_TEST_KILL_COMMIT_AT", std::to_string(k).c_str(), 1);
    r = run_cli("simulate " + scene.string() + " --out " + out.string());
    ::unsetenv("TIGHTFIT_TEST_KILL_COMMIT_AT");
    killed += r.exit_code != 0 ? 1 : 0;
    if (inode(out) == folder_before) {
      EXPECT_EQ(contents(out), before) << "kill at step " << k;  // untouched
    } else {
      const auto after = contents(out);  // complete: every output new, the notes kept
      EXPECT_EQ(after.size(), names.size()) << "kill at step " << k;
      EXPECT_EQ(after.at("notes.txt"), "mine");
      EXPECT_NE(after.at("result.json"), before.at("result.json")) << "kill at step " << k;
    }
  }
  EXPECT_EQ(killed, 8);  // the commit has a step per entry it keeps (11), then the swap
  // A run without the hook removes the killed runs' staging folders.
  r = run_cli("simulate " + scene.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tightfit-"), std::string::npos) << e.path();
}

TEST_F(RunSafetyCli, ASecondRunIntoABusyFolderIsRefusedNamingTheFirst) {
  const fs::path scene = write("opt.json", optimize_scene(200));
  const fs::path sim = write("scene.json", sleeve_scene());
  const fs::path out = dir_ / "out";
  ASSERT_EQ(bash(std::string(TIGHTFIT_CLI) + " optimize " + scene.string() + " --out " +
                 out.string() + " > " + (dir_ / "first.txt").string() + " 2>&1 & pid=$!; " +
                 "for i in $(seq 1 600); do [ -f " + (out / "history.json").string() +
                 " ] && break; sleep 0.05; done; " + TIGHTFIT_CLI + " simulate " + sim.string() +
                 " --out " + out.string() + " > " + (dir_ / "second.txt").string() +
                 " 2>&1; echo $? > " + (dir_ / "code.txt").string() + "; echo $pid > " +
                 (dir_ / "pid.txt").string() + "; kill -KILL $pid; wait $pid; true"),
            0);
  const std::string second = read_text(dir_ / "second.txt");
  std::string pid = read_text(dir_ / "pid.txt");
  pid.erase(pid.find_last_not_of("\n") + 1);
  EXPECT_EQ(read_text(dir_ / "code.txt"), "2\n") << second;
  EXPECT_NE(second.find("is in use by another tightfit run (process " + pid + " holds its lock)"),
            std::string::npos)
      << second << read_text(dir_ / "first.txt");
  EXPECT_FALSE(fs::exists(out / "result.json"));  // the second run wrote nothing
}

TEST_F(RunSafetyCli, ResumeRefusesACheckpointOfOtherInputsNamingTheFile) {
  const fs::path out = dir_ / "out";
  const fs::path scene = write("opt.json", optimize_scene(1));
  CliRun r = run_cli("optimize " + scene.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // More iterations only: the same inputs.
  const fs::path longer = write("longer.json", optimize_scene(2));
  r = run_cli("optimize " + longer.string() + " --out " + (dir_ / "a").string() + " --resume " +
              out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // A stiffer fabric with the same objective terms: refused, naming the scene file.
  nlohmann::json stiffer = optimize_scene(2);
  stiffer["fabric"] = {{"youngs_modulus", 2e6}};
  const fs::path other = write("stiffer.json", stiffer);
  r = run_cli("optimize " + other.string() + " --out " + (dir_ / "b").string() + " --resume " +
              out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("checkpoint.json: was written for other inputs"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("stiffer.json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "b"));
  // A checkpoint with an absurd coordinate: an input error naming the file and the place.
  nlohmann::json checkpoint = nlohmann::json::parse(read_text(out / "checkpoint.json"));
  checkpoint["state"]["body"][0][0] = 1e9;
  fs::create_directories(dir_ / "absurd");
  std::ofstream(dir_ / "absurd" / "checkpoint.json") << checkpoint.dump();
  r = run_cli("optimize " + scene.string() + " --out " + (dir_ / "d").string() + " --resume " +
              (dir_ / "absurd").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("absurd/checkpoint.json: /state/body/0/0 is 1e+09 m"), std::string::npos)
      << r.output;
  // The same scene file edited in place: refused, naming the file that changed.
  std::ofstream(scene) << stiffer.dump(2);
  r = run_cli("optimize " + scene.string() + " --out " + (dir_ / "c").string() + " --resume " +
              out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fs::weakly_canonical(scene).string() + " changed since"),
            std::string::npos)
      << r.output;
}

TEST_F(RunSafetyCli, AFailedOptimizeIntoANewFolderLeavesNoFolder) {
  nlohmann::json s = optimize_scene(2);
  s["solver"] = {{"max_iterations", 1}};
  const fs::path scene = write("failing.json", s);
  const CliRun r = run_cli("optimize " + scene.string() + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tightfit-"), std::string::npos) << e.path();
}

TEST_F(RunSafetyCli, TheInterruptHintIsACommandThatWorksWhenPasted) {
  // The sphere-pressure example (about 0.7 s per iteration), interrupted once iteration 1
  // is reported, into a folder whose name needs quoting.
  const fs::path scene = fs::path(TIGHTFIT_SOURCE_DIR) / "examples/optimize_sphere_pressure.json";
  const fs::path log = dir_ / "log.txt";
  const std::string out = "my run";
  ASSERT_EQ(bash("cd " + dir_.string() + "; " + TIGHTFIT_CLI + " optimize " + scene.string() +
                 " --out '" + out + "' --max-iterations 6 > " + log.string() +
                 " 2>&1 & pid=$!; for i in $(seq 1 600); do grep -q '^ *1/6 ' " + log.string() +
                 " && break; sleep 0.05; done; kill -INT $pid; wait $pid; true"),
            0);
  const std::string text = read_text(log);
  const std::size_t at = text.find("continue with\n    ");
  ASSERT_NE(at, std::string::npos) << text;
  std::string command = text.substr(at + 18);
  command.erase(command.find('\n'));
  EXPECT_NE(command.find("--out 'my run' --resume 'my run'"), std::string::npos) << command;
  EXPECT_NE(command.find("--max-iterations 6"), std::string::npos) << command;
  ASSERT_TRUE(command.starts_with("tightfit optimize "));
  command.replace(0, 8, TIGHTFIT_CLI);
  EXPECT_EQ(bash("cd " + dir_.string() + " && " + command + " > " + log.string() + " 2>&1"), 0)
      << read_text(log);
  const nlohmann::json result = nlohmann::json::parse(read_text(dir_ / out / "result.json"));
  EXPECT_EQ(result["optimization"]["iterations"].get<int>(), 6);
  EXPECT_FALSE(result["optimization"]["interrupted"].get<bool>());
}

TEST_F(RunSafetyCli, InputsThatAreNotRegularFilesAreRefusedAtOnce) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo.obj").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir_ / "zero.obj");
  for (const char* mesh : {"fifo.obj", "zero.obj"}) {
    nlohmann::json s = sleeve_scene();
    s["body"] = {{"mesh", mesh}, {"edge_length", 0.02}};
    const fs::path scene = write("scene.json", s);
    const CliRun r = run_cli("simulate " + scene.string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
  }
  // A scene that is a FIFO too.
  ASSERT_EQ(::mkfifo((dir_ / "scene_fifo.json").c_str(), 0600), 0);
  const CliRun r = run_cli("simulate " + (dir_ / "scene_fifo.json").string() + " --out " +
                           (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace tightfit::run_safety_cli_test
