/// `tightfit grade` with the built CLI on three small bodies: the male legs (coarse, the
/// four-panel anchored left leg, two iterations) scaled to 0.92, 1 and 1.08 with their
/// rig mesh and joints. Graded through GNU parallel (two jobs, joblog, --resume-failed)
/// and gathered; one body at a time for skipping, resuming and determinism; and with
/// failing bodies next to a good one.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/shell_command.hpp"

namespace tightfit {
namespace grade_test {

namespace fs = std::filesystem;

/// The OBJ file `from` with every vertex scaled by `s` about the origin (the floor
/// under the body), written to `to`.
void write_scaled_obj(const fs::path& from, const fs::path& to, double s) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream words(line.substr(2));
      double x = 0, y = 0, z = 0;
      words >> x >> y >> z;
      out << "v " << x * s << " " << y * s << " " << z * s << "\n";
    } else {
      out << line << "\n";
    }
  }
}

/// The joints file `from` with every head and tail scaled by `s`, written to `to`.
void write_scaled_joints(const fs::path& from, const fs::path& to, double s) {
  std::ifstream in(from);
  nlohmann::json j = nlohmann::json::parse(in);
  for (auto& [name, bone] : j["bones"].items())
    for (const char* end : {"head", "tail"})
      for (auto& c : bone[end]) c = c.get<double>() * s;
  std::ofstream(to) << j.dump();
}

class GradeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_grade_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const fs::path data(TIGHTFIT_DATA_DIR), source(TIGHTFIT_SOURCE_DIR);
    const nlohmann::json design = {
        {"body",
         {{"mesh", (data / "bodies/mh_legs_male.obj").string()},
          {"edge_length", 0.04},
          {"core", {{"soft_tissue", 0.015}}}}},
        {"garment",
         {{"layout", (source / "examples/layouts/left_leg_anchored.json").string()},
          {"pattern", {{"edge_length", 0.045}, {"scale", {0.95, 0.85}}, {"grain", {0, 1, 0}}}}}},
        {"rig",
         {{"mesh", (data / "bodies/mh_male_regular.obj").string()},
          {"weights", (data / "rig/default_weights.mhw").string()},
          {"joints", (data / "rig/mh_male_regular.joints.json").string()}}},
        {"optimize",
         {{"objectives", {{"stretch", {{"weight", 1}, {"min", 1.05}, {"max", 1.15}}}}},
          {"max_iterations", 2},
          {"checkpoint_every", 1}}}};
    std::ofstream(dir_ / "design.json") << design.dump(2);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A body of the legs scaled by `s`: its mesh, rig mesh and joints in the test folder.
  nlohmann::json scaled_legs(const std::string& name, double s) {
    const fs::path data(TIGHTFIT_DATA_DIR);
    write_scaled_obj(data / "bodies/mh_legs_male.obj", dir_ / (name + "_legs.obj"), s);
    write_scaled_obj(data / "bodies/mh_male_regular.obj", dir_ / (name + "_full.obj"), s);
    write_scaled_joints(data / "rig/mh_male_regular.joints.json", dir_ / (name + ".joints.json"),
                        s);
    return {{"name", name},
            {"mesh", name + "_legs.obj"},
            {"rig_mesh", name + "_full.obj"},
            {"joints", name + ".joints.json"}};
  }
  fs::path write_bodies(const nlohmann::json& bodies) {
    std::ofstream(dir_ / "bodies.json") << nlohmann::json{{"bodies", bodies}}.dump(2);
    return dir_ / "bodies.json";
  }
  std::string grade_args(const fs::path& out) const {
    return "grade " + (dir_ / "design.json").string() + " " + (dir_ / "bodies.json").string() +
           " --out " + out.string();
  }
  static nlohmann::json read_json(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
  }

  fs::path dir_;
};

TEST_F(GradeCli, ThreeBodiesThroughGnuParallelWithTwoJobsThenGathered) {
  ASSERT_EQ(test::run_command("parallel --version").exit_code, 0)
      << "GNU parallel is missing: scripts/install-deps.sh installs it";
  write_bodies(nlohmann::json::array(
      {scaled_legs("small", 0.92), scaled_legs("medium", 1.0), scaled_legs("large", 1.08)}));
  const fs::path out = dir_ / "graded", joblog = dir_ / "joblog.txt";
  const std::string command = "parallel --jobs 2 --joblog " + test::shell_quote(joblog) +
                              " --resume-failed " + std::string(TIGHTFIT_CLI) + " --threads 1 " +
                              grade_args(out) + " --body {} ::: small medium large";
  const test::CommandResult run = test::run_command(command);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The joblog: a header and one line per body, each with exit value 0.
  std::ifstream log(joblog);
  std::string line;
  std::getline(log, line);
  int jobs = 0;
  while (std::getline(log, line)) {
    std::istringstream fields(line);
    std::string seq, host, start, runtime, send, receive, exitval;
    fields >> seq >> host >> start >> runtime >> send >> receive >> exitval;
    EXPECT_EQ(exitval, "0") << line;
    ++jobs;
  }
  EXPECT_EQ(jobs, 3);

  const test::CliRun gathered = test::run_cli(grade_args(out) + " --gather");
  ASSERT_EQ(gathered.exit_code, 0) << gathered.output;
  const nlohmann::json grade = read_json(out / "grade.json");
  EXPECT_EQ(grade["format"], "tightfit-grade");
  EXPECT_EQ(grade["counts"]["done"], 3);
  ASSERT_EQ(grade["bodies"].size(), 3u);
  for (const auto& body : grade["bodies"]) {
    EXPECT_EQ(body["status"], "done") << body.dump();
    EXPECT_EQ(body["iterations"], 2);
    EXPECT_LT(body["objective"]["final"].get<double>(), body["objective"]["initial"].get<double>());
    EXPECT_GT(body["pressure_mmhg"]["median"].get<double>(), 0.0);
    EXPECT_GT(body["stretch_max"]["median"].get<double>(), 1.0);
    EXPECT_GT(body["seconds"]["initial_solve"].get<double>(), 0.0);
  }
  // The four panels have six seams, each with its size-to-size change. The cuts follow
  // each body's coarse mesh, so one seam may change little; all together they grow with
  // the body, about in proportion.
  ASSERT_EQ(grade["seams"].size(), 6u);
  std::map<std::string, double> total;
  for (const auto& seam : grade["seams"]) {
    EXPECT_FALSE(seam["change_mm"].contains("small"));
    for (const char* size : {"medium", "large"})
      EXPECT_TRUE(seam["change_mm"].contains(size)) << seam.dump();
    for (const char* size : {"small", "medium", "large"})
      total[size] += seam["length_mm"][size].get<double>();
    EXPECT_NEAR(
        seam["change_mm"]["large"].get<double>(),
        seam["length_mm"]["large"].get<double>() - seam["length_mm"]["medium"].get<double>(), 1e-9);
  }
  EXPECT_LT(total["small"], total["medium"]);
  EXPECT_LT(total["medium"], total["large"]);
  EXPECT_NEAR(total["large"] / total["small"], 1.08 / 0.92, 0.06)
      << total["small"] << " " << total["medium"] << " " << total["large"];
  // Girths at the skeleton's standard levels grow with the body (scaled 0.92 / 1.0 / 1.08),
  // the ease (one design, one fabric) stays about the same.
  std::map<std::string, std::map<std::string, double>> girth, ease;  // level -> body -> value
  for (const auto& body : grade["bodies"]) {
    ASSERT_FALSE(body["measurements"].empty()) << body.dump();
    for (const auto& m : body["measurements"]) {
      girth[m["name"].get<std::string>()][body["name"].get<std::string>()] =
          m["body_circumference_m"].get<double>();
      ease[m["name"].get<std::string>()][body["name"].get<std::string>()] =
          m["ease_percent"].get<double>();
    }
  }
  int compared = 0;
  for (const auto& [level, by_body] : girth) {
    if (by_body.size() != 3) continue;
    ++compared;
    EXPECT_NEAR(by_body.at("large") / by_body.at("small"), 1.08 / 0.92, 0.05) << level;
    EXPECT_NEAR(ease[level].at("large"), ease[level].at("small"), 5.0) << level;
  }
  EXPECT_GT(compared, 0);
  const std::string html = test::read_text(out / "grade.html");
  for (const char* text : {"small", "medium", "large", "Nest", "thigh_front", "<svg",
                           "Girths and negative ease", " cm, -"})
    EXPECT_NE(html.find(text), std::string::npos) << text;
  // Every exported nest holds the four pieces of the three sizes.
  const std::string svg = test::read_text(out / "nest.svg"),
                    dxf = test::read_text(out / "nest.dxf");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_EQ(test::read_text(out / "nest.pdf").rfind("%PDF", 0), 0u);
  for (const char* piece : {"thigh_front/small", "thigh_front/large", "lower_leg_back/medium"})
    EXPECT_NE(dxf.find(piece), std::string::npos) << piece;

  // The nest aligned at the start of a seam; an unknown seam is bad input.
  const test::CliRun seam =
      test::run_cli(grade_args(out) + " --gather --nest-seam thigh_front/thigh_back");
  EXPECT_EQ(seam.exit_code, 0) << seam.output;
  EXPECT_NE(test::read_text(out / "grade.html").find("the start of seam thigh_front/thigh_back"),
            std::string::npos);
  const test::CliRun no_seam = test::run_cli(grade_args(out) + " --gather --nest-seam hem");
  EXPECT_EQ(no_seam.exit_code, 2);
  EXPECT_NE(no_seam.output.find("--nest-seam: no seam \"hem\" in the pattern of small"),
            std::string::npos)
      << no_seam.output;

  // --resume-failed runs nothing again: every job succeeded.
  const test::CommandResult again = test::run_command(command);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  std::ifstream log_again(joblog);
  int lines = 0;
  while (std::getline(log_again, line)) ++lines;
  EXPECT_EQ(lines, 4);
}

TEST_F(GradeCli, AGradedBodyIsSkippedAKilledOneResumesAndTheSameInputsGiveTheSameOutputs) {
  write_bodies(nlohmann::json::array({scaled_legs("medium", 1.0)}));
  const fs::path out = dir_ / "graded";
  const fs::path folder = out / "bodies" / "medium";
  // Killed after its first checkpoint (SIGKILL: no chance to write anything more).
  const std::string command = std::string(TIGHTFIT_CLI) + " --threads 1 " + grade_args(out) +
                              " --body medium --max-iterations 4 > /dev/null 2>&1";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(folder / "checkpoint.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(folder / "checkpoint.json"));
  // Killed long before its last iteration: its status says it is still running.
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(read_json(folder / "grade_body.json")["status"], "running");
  EXPECT_FALSE(fs::exists(folder / "pieces.json"));

  const test::CliRun resumed =
      test::run_cli("--threads 1 " + grade_args(out) + " --body medium --max-iterations 4");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming from its checkpoint"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(read_json(folder / "grade_body.json")["status"], "done");
  EXPECT_EQ(read_json(folder / "result.json")["optimization"]["iterations"], 4);
  const std::string pieces = test::read_text(folder / "pieces.json");
  const auto written = fs::last_write_time(folder / "pieces.json");

  // Again: skipped, nothing rewritten.
  const test::CliRun skipped =
      test::run_cli("--threads 1 " + grade_args(out) + " --body medium --max-iterations 4");
  EXPECT_EQ(skipped.exit_code, 0) << skipped.output;
  EXPECT_NE(skipped.output.find("graded already"), std::string::npos) << skipped.output;
  EXPECT_EQ(fs::last_write_time(folder / "pieces.json"), written);

  // Other inputs (another iteration limit): graded afresh, not skipped.
  const test::CliRun other =
      test::run_cli("--threads 1 " + grade_args(out) + " --body medium --max-iterations 1");
  EXPECT_EQ(other.exit_code, 0) << other.output;
  EXPECT_EQ(other.output.find("graded already"), std::string::npos) << other.output;
  EXPECT_EQ(read_json(folder / "result.json")["optimization"]["iterations"], 1);

  // The same inputs in another folder, without interruption: the same pattern.
  const fs::path fresh = dir_ / "fresh";
  const test::CliRun straight =
      test::run_cli("--threads 1 " + grade_args(fresh) + " --body medium --max-iterations 4");
  ASSERT_EQ(straight.exit_code, 0) << straight.output;
  const nlohmann::json a = nlohmann::json::parse(pieces);
  const nlohmann::json b = read_json(fresh / "bodies" / "medium" / "pieces.json");
  ASSERT_EQ(a["pieces"].size(), b["pieces"].size());
  for (size_t p = 0; p < a["pieces"].size(); ++p) {
    const auto& ra = a["pieces"][p]["rest"];
    const auto& rb = b["pieces"][p]["rest"];
    ASSERT_EQ(ra.size(), rb.size());
    for (size_t i = 0; i < ra.size(); ++i)
      for (int c = 0; c < 2; ++c) EXPECT_NEAR(ra[i][c].get<double>(), rb[i][c].get<double>(), 1e-9);
  }
}

TEST_F(GradeCli, SigtermToALocalRunStopsItsBodiesAtACheckpointAndTheNextRunResumesThem) {
  write_bodies(nlohmann::json::array({scaled_legs("small", 0.92), scaled_legs("large", 1.08)}));
  const fs::path out = dir_ / "graded";
  const std::string args = grade_args(out) + " --jobs 2 --max-iterations 8";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string command =
        "exec " + std::string(TIGHTFIT_CLI) + " --threads 2 " + args + " > /dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto started = [&] {
    return fs::exists(out / "bodies/small/checkpoint.json") &&
           fs::exists(out / "bodies/large/checkpoint.json");
  };
  while (!started() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  // Each body finished its iteration, wrote its checkpoint and stayed "running".
  for (const char* name : {"small", "large"}) {
    EXPECT_EQ(read_json(out / "bodies" / name / "grade_body.json")["status"], "running") << name;
    EXPECT_NE(
        test::read_text(out / "logs" / (std::string(name) + ".log")).find("interrupted by SIGTERM"),
        std::string::npos)
        << name;
  }
  const test::CliRun resumed = test::run_cli("--threads 2 " + args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  for (const char* name : {"small", "large"}) {
    EXPECT_NE(test::read_text(out / "logs" / (std::string(name) + ".log"))
                  .find("resuming from its checkpoint"),
              std::string::npos)
        << name;
    EXPECT_EQ(read_json(out / "bodies" / name / "result.json")["optimization"]["iterations"], 8)
        << name;
  }
  EXPECT_EQ(read_json(out / "grade.json")["counts"]["done"], 2);
}

TEST_F(GradeCli, FailingBodiesAreRecordedAndTheOthersAreGraded) {
  nlohmann::json alien = scaled_legs("alien", 1.0);
  // Another body's skeleton, twice too large: its joints lie outside this body.
  write_scaled_joints(fs::path(TIGHTFIT_DATA_DIR) / "rig/mh_child.joints.json",
                      dir_ / "alien.joints.json", 2.0);
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  const nlohmann::json broken = {
      {"name", "broken"},
      {"mesh", "broken.obj"},
      {"joints", (fs::path(TIGHTFIT_DATA_DIR) / "rig/mh_male_regular.joints.json").string()}};
  // A head with the man's rig: the leg layout cannot be placed on it.
  const fs::path data(TIGHTFIT_DATA_DIR);
  const nlohmann::json head = {{"name", "head"},
                               {"mesh", (data / "bodies/mh_head_neutral.obj").string()},
                               {"rig_mesh", (data / "bodies/mh_male_regular.obj").string()},
                               {"joints", (data / "rig/mh_male_regular.joints.json").string()}};
  write_bodies(nlohmann::json::array({scaled_legs("medium", 1.0), alien, broken, head}));
  const fs::path out = dir_ / "graded";
  const test::CliRun r = test::run_cli("--threads 2 " + grade_args(out) + " --jobs 2");
  EXPECT_EQ(r.exit_code, 13) << r.output;
  const nlohmann::json grade = read_json(out / "grade.json");
  EXPECT_EQ(grade["counts"]["done"], 1);
  EXPECT_EQ(grade["counts"]["failed"], 3);
  EXPECT_EQ(grade["bodies"][0]["status"], "done");
  const std::string alien_error = grade["bodies"][1]["error"];
  EXPECT_NE(alien_error.find("alien.joints.json"), std::string::npos) << alien_error;
  EXPECT_NE(alien_error.find("outside"), std::string::npos) << alien_error;
  const std::string broken_error = grade["bodies"][2]["error"];
  EXPECT_NE(broken_error.find("broken.obj"), std::string::npos) << broken_error;
  const std::string head_error = grade["bodies"][3]["error"];
  EXPECT_NE(
      head_error.find("left_leg_anchored.json: /dividers/0: divider \"thigh\" misses the body"),
      std::string::npos)
      << head_error;
  // A failed body's folder holds its scene and status only.
  for (const char* name : {"alien", "broken", "head"}) {
    std::set<std::string> files;
    for (const auto& e : fs::directory_iterator(out / "bodies" / name))
      files.insert(e.path().filename().string());
    EXPECT_EQ(files,
              (std::set<std::string>{".grade.lock", ".tightfit", "grade_body.json", "scene.json"}))
        << name;
  }
  EXPECT_NE(test::read_text(out / "grade.html").find(alien_error.substr(0, 40)), std::string::npos);
  // Gathering alone says the same.
  EXPECT_EQ(test::run_cli(grade_args(out) + " --gather").exit_code, 13);
}

TEST_F(GradeCli, TwoBodiesOfOneNameOrAnUnknownBodyAreErrorsBeforeAnythingIsWritten) {
  write_bodies(nlohmann::json::array({scaled_legs("medium", 1.0), scaled_legs("medium", 1.0)}));
  const fs::path out = dir_ / "graded";
  const test::CliRun r = test::run_cli(grade_args(out) + " --jobs 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bodies.json: /bodies/1/name: two bodies are named \"medium\""),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  write_bodies(nlohmann::json::array({scaled_legs("medium", 1.0)}));
  const test::CliRun unknown = test::run_cli(grade_args(out) + " --body mediun");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("did you mean \"medium\""), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace grade_test
}  // namespace tightfit
