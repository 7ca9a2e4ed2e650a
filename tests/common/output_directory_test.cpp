#include "tightfit/common/output_directory.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/staging_folder.hpp"

namespace tightfit::test::output_directory_test {

namespace fs = std::filesystem;

/// A fresh folder under the temporary directory, unique to this process and `name`.
fs::path fresh(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_outdir_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every entry under `folder` (recursively) with its content ("<dir>" for folders,
/// "-> TARGET" for links): what an observer of the folder sees.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> entries;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(folder, ec))) return {{"", "<missing>"}};
  for (auto it = fs::recursive_directory_iterator(folder, ec); it != fs::end(it); ++it) {
    const std::string name = fs::relative(it->path(), folder).string();
    if (it->is_symlink())
      entries[name] = "-> " + fs::read_symlink(it->path()).string();
    else if (it->is_directory())
      entries[name] = "<dir>";
    else
      entries[name] = read_text(it->path());
  }
  return entries;
}

std::size_t count_entries(const fs::path& folder) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++n;
  return n;
}

TEST(OutputDirectory, IsAllOrNothingAndDeletesNothing) {
  const fs::path target = fresh("all_or_nothing") / "out";
  {
    OutputDirectory out(target);
    write_text_atomically(out.file("a.txt"), "a");
  }  // no commit: nothing appears, not even the folder it would have created
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(count_entries(target.parent_path()), 0u);  // no staging folder left beside it
  {
    OutputDirectory out(target);
    write_text_atomically(out.file("b.txt"), "b");
    EXPECT_EQ(out.commit(), std::vector<std::string>{"b.txt"});
  }
  EXPECT_EQ(read_text(target / "b.txt"), "b");
  EXPECT_TRUE(fs::exists(target / kOutputMarker));
  {
    OutputDirectory out(target);  // a tightfit folder now: accepted
    write_text_atomically(out.file("c.txt"), "c");
    write_text_atomically(out.file("b.txt"), "new b");
    out.commit();
  }
  EXPECT_EQ(read_text(target / "c.txt"), "c");
  EXPECT_EQ(read_text(target / "b.txt"), "new b");  // replaced; nothing else removed
  EXPECT_EQ(count_entries(target), 3u);             // b.txt, c.txt, the marker
  EXPECT_EQ(count_entries(target.parent_path()), 1u);
  fs::remove_all(target.parent_path());
}

TEST(OutputDirectory, AnObstacleIsFoundBeforeAnythingChanges) {
  const fs::path target = fresh("obstacle");
  std::ofstream(target / kOutputMarker) << "x";
  for (const char* name : {"a.txt", "b.txt", "c.txt"}) std::ofstream(target / name) << "old";
  fs::create_directories(target / "pattern.svg");  // a folder where a file goes
  const auto before = snapshot(target);
  {
    OutputDirectory out(target);
    for (const char* name : {"a.txt", "b.txt", "c.txt", "pattern.svg"})
      write_text_atomically(out.file(name), "new");
    try {
      out.commit();
      ADD_FAILURE() << "the obstacle was not noticed";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("pattern.svg"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(snapshot(target), before);
  fs::remove_all(target);
}

TEST(OutputDirectory, ReplacesPlantedLinksInsteadOfFollowingThem) {
  const fs::path dir = fresh("links");
  const fs::path target = dir / "out", victim = dir / "victim.txt";
  fs::create_directories(target);
  std::ofstream(target / kOutputMarker) << "x";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, target / "result.json");
  {
    OutputDirectory out(target);
    write_text_atomically(out.file("result.json"), "{}");
    out.commit();
  }
  EXPECT_EQ(read_text(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(target / "result.json"));
  EXPECT_EQ(read_text(target / "result.json"), "{}");
  // An atomic write replaces a link at its own name too, and its temporary files have
  // names that cannot be guessed (not derived from the process id).
  fs::create_symlink(victim, dir / "history.json");
  write_text_atomically(dir / "history.json", "[]");
  EXPECT_EQ(read_text(victim), "precious");
  EXPECT_EQ(read_text(dir / "history.json"), "[]");
  const fs::path t1 = temporary_path_for(dir / "a.pdf"), t2 = temporary_path_for(dir / "a.pdf");
  EXPECT_NE(t1, t2);
  EXPECT_EQ(t1.filename().string().find(std::to_string(::getpid())), std::string::npos);
  fs::remove_all(dir);
}

TEST(OutputDirectory, NeverRemovesAUsersEntryThatLooksLikeATemporary) {
  const fs::path dir = fresh("lookalikes");
  const fs::path target = dir / "out";
  fs::create_directories(target / "archive.tmp.999999.1");
  std::ofstream(target / "archive.tmp.999999.1" / "thesis.tex") << "years of work";
  std::ofstream(target / "draft.txt.tmp.888888.0") << "draft";
  fs::create_directories(target / ".tightfit-staging.999999.0");
  std::ofstream(target / ".tightfit-staging.999999.0" / "mine") << "mine";
  fs::create_directories(dir / ".out.tightfit-AbCdEf");  // named like a staging folder
  std::ofstream(dir / ".out.tightfit-AbCdEf" / "tightfit-staging") << "not a manifest";
  // A folder holding only a look-alike is not tightfit's.
  const fs::path only = dir / "only";
  fs::create_directories(only / ".tightfit-staging.999999.0");
  EXPECT_FALSE(is_tightfit_folder(only));
  // A real staging folder of a killed run (its process is gone): removed by the next run.
  const pid_t child = ::fork();
  if (child == 0) {
    const fs::path real = fs::weakly_canonical(target);
    make_staging_folder(real, real.parent_path());
    ::_exit(0);  // its lock dies with it; the folder stays, as after a SIGKILL
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_EQ(count_entries(dir), 4u);  // out, only, the look-alike, the abandoned one
  {
    OutputDirectory out(target, true);
    write_text_atomically(out.file("result.json"), "{}");
    out.commit();
  }
  EXPECT_EQ(read_text(target / "archive.tmp.999999.1" / "thesis.tex"), "years of work");
  EXPECT_EQ(read_text(target / "draft.txt.tmp.888888.0"), "draft");
  EXPECT_EQ(read_text(target / ".tightfit-staging.999999.0" / "mine"), "mine");
  EXPECT_EQ(read_text(dir / ".out.tightfit-AbCdEf" / "tightfit-staging"), "not a manifest");
  EXPECT_EQ(count_entries(dir), 3u);  // the abandoned staging folder is gone
  fs::remove_all(dir);
}

TEST(OutputDirectory, OneWriterPerFolder) {
  const fs::path target = fresh("one_writer");
  OutputDirectory first(target);
  try {
    OutputDirectory second(target);
    ADD_FAILURE() << "two writers were let in";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("process " + std::to_string(::getpid())),
              std::string::npos)
        << e.what();
  }
  // Two runs into a folder that did not exist: the second to finish is refused.
  const fs::path missing = target.parent_path() / (target.filename().string() + "_new");
  fs::remove_all(missing);
  OutputDirectory a(missing), b(missing);
  write_text_atomically(a.file("x.txt"), "a");
  write_text_atomically(b.file("x.txt"), "b");
  a.commit();
  EXPECT_THROW(b.commit(), InputError);
  EXPECT_EQ(read_text(missing / "x.txt"), "a");
  fs::remove_all(missing);
  fs::remove_all(target);
}

TEST(OutputDirectory, PublishedFilesOfAFailedRunInANewFolderAreRemoved) {
  const fs::path target = fresh("publish") / "out";
  {
    OutputDirectory out(target);
    out.publish("history.json", [](const fs::path& p) { write_text_atomically(p, "[1]"); });
    EXPECT_EQ(read_text(target / "history.json"), "[1]");
    out.publish("history.json", [](const fs::path& p) { write_text_atomically(p, "[1,2]"); });
    EXPECT_EQ(read_text(target / "history.json"), "[1,2]");
    EXPECT_THROW(OutputDirectory{target}, InputError);  // locked from its first moment
  }
  EXPECT_FALSE(fs::exists(target));
  {
    OutputDirectory out(target);
    out.publish("checkpoint.json", [](const fs::path& p) { write_text_atomically(p, "{}"); });
    out.keep_published();  // a resumable failure
  }
  EXPECT_EQ(read_text(target / "checkpoint.json"), "{}");
  EXPECT_TRUE(is_tightfit_folder(target));
  fs::remove_all(target.parent_path());
}

TEST(OutputDirectory, RefusesFoldersTightfitDidNotMakeUnlessForced) {
  const fs::path target = fresh("user");
  write_text_atomically(target / "thesis.tex", "mine");
  try {
    OutputDirectory out(target);
    ADD_FAILURE() << "a user's folder was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--force"), std::string::npos) << e.what();
  }
  {
    OutputDirectory out(target, true);
    write_text_atomically(out.file("result.json"), "{}");
    out.commit();
  }
  EXPECT_TRUE(fs::exists(target / "thesis.tex"));
  EXPECT_TRUE(fs::exists(target / "result.json"));
  // A folder holding a tightfit state.json (an earlier version's run) is a tightfit folder.
  const fs::path old_run = fresh("old_run");
  write_text_atomically(old_run / "state.json",
                        R"({"command": "simulate", "format": "tightfit-run-state"})");
  EXPECT_TRUE(is_tightfit_folder(old_run));
  write_text_atomically(old_run / "state.json", R"({"format": "something else"})");
  EXPECT_FALSE(is_tightfit_folder(old_run));
  // A file is not a folder; "dir/." is the folder itself.
  EXPECT_THROW(OutputDirectory{target / "thesis.tex"}, InputError);
  {
    OutputDirectory out(target / ".", true);
    write_text_atomically(out.file("dot.txt"), "d");
    out.commit();
  }
  EXPECT_TRUE(fs::exists(target / "dot.txt"));
  fs::remove_all(target);
  fs::remove_all(old_run);
}

/// Runs one commit in a child process that SIGKILLs itself before its `kill_at`-th change
/// to the file system; returns whether the kill happened.
bool commit_killed_at(const fs::path& target, long kill_at, const std::vector<std::string>& files) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::setenv("TIGHTFIT_TEST_KILL_COMMIT_AT", std::to_string(kill_at).c_str(), 1);
    try {
      OutputDirectory out(target);
      for (const std::string& name : files) write_text_atomically(out.file(name), "new " + name);
      fs::create_directories(out.file("patterns"));
      write_text_atomically(out.file("patterns") / "a.svg", "new svg");
      out.commit();
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0));
  return WIFSIGNALED(status);
}

TEST(OutputDirectory, AKilledCommitLeavesTheFolderAsItWasOrComplete) {
  const fs::path dir = fresh("killed");
  const fs::path target = dir / "out";
  std::vector<std::string> files;
  for (int k = 0; k < 10; ++k) files.push_back("file" + std::to_string(k) + ".txt");
  // The complete result, and the folder before: an earlier run's files and 24 of the
  // user's, so that the commit has many moments to be killed at.
  const fs::path reference = dir / "reference";
  ASSERT_FALSE(commit_killed_at(reference, -1, files));
  const auto complete_new = snapshot(reference);
  auto make_before = [&] {
    fs::remove_all(target);
    fs::create_directories(target / "patterns");
    std::ofstream(target / kOutputMarker) << "old marker";
    for (const std::string& name : files) std::ofstream(target / name) << "old " << name;
    std::ofstream(target / "patterns" / "a.svg") << "old svg";
    for (int k = 0; k < 24; ++k) std::ofstream(target / ("user" + std::to_string(k))) << k;
    fs::create_directories(target / "user_folder");
    std::ofstream(target / "user_folder" / "notes") << "notes";
  };
  make_before();
  const auto before = snapshot(target);
  std::mt19937 random(12345);
  int killed_existing = 0, killed_new = 0;
  std::vector<long> points;
  for (long k = 0; k < 28; ++k) points.push_back(k);
  for (int k = 0; k < 12; ++k) points.push_back(static_cast<long>(random() % 30));
  for (const long k : points) {
    make_before();
    killed_existing += commit_killed_at(target, k, files) ? 1 : 0;
    auto after = snapshot(target);
    if (after != before) {
      // Complete: the new files, and every entry of the user's as it was.
      for (const auto& [name, content] : complete_new)
        EXPECT_EQ(after[name], content) << "kill at step " << k << ": " << name;
      for (const auto& [name, content] : before) {
        if (name.starts_with("user")) {
          EXPECT_EQ(after[name], content) << "kill at " << k;
        }
      }
      EXPECT_EQ(after.size(), before.size()) << "kill at step " << k;
    }
    fs::remove_all(target);
    killed_new += commit_killed_at(target, k, files) ? 1 : 0;
    after = snapshot(target);
    if (after != snapshot(dir / "no such folder")) {
      EXPECT_EQ(after, complete_new) << "kill " << k;
    }
  }
  EXPECT_GE(killed_existing, 20);  // the kills did hit the commit
  EXPECT_GE(killed_new, 1);
  // The staging folders the kills left beside the target are removed by the next run.
  make_before();
  {
    OutputDirectory out(target);
    out.commit();
  }
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path().filename() == "out" || e.path().filename() == "reference") << e.path();
  fs::remove_all(dir);
}

}  // namespace tightfit::test::output_directory_test
