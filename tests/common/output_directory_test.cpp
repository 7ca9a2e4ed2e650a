#include "tightfit/common/output_directory.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::test::output_directory_test {

TEST(OutputDirectory, RemovesOnlyWhatKilledRunsLeftUnfinished) {
  namespace fs = std::filesystem;
  const auto folder = fs::temp_directory_path() / ("tightfit_stale_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder / ".tightfit-staging.999999999.0");  // no such process
  const std::string own = std::to_string(::getpid());
  const std::vector<std::string> kept = {"state.json.tmp." + own + ".1", "notes.tmp",
                                         "photo.tmp.12.jpg", "result.json"};
  for (const std::string& name : kept) std::ofstream(folder / name) << "x";
  std::ofstream(folder / "report.html.tmp.999999999.3") << "x";
  EXPECT_EQ(remove_stale_temporaries(folder), 2);
  EXPECT_FALSE(fs::exists(folder / ".tightfit-staging.999999999.0"));
  EXPECT_FALSE(fs::exists(folder / "report.html.tmp.999999999.3"));
  // A live writer's file (this process), and names tightfit does not give, stay.
  for (const std::string& name : kept) EXPECT_TRUE(fs::exists(folder / name)) << name;
  fs::remove_all(folder);
}

TEST(OutputDirectory, IsAllOrNothingAndDeletesNothing) {
  const auto target = std::filesystem::temp_directory_path() / "tightfit_outdir_test";
  std::filesystem::remove_all(target);
  {
    OutputDirectory out(target);
    write_text_atomically(out.file("a.txt"), "a");
  }  // no commit: nothing appears, not even the folder it created
  EXPECT_FALSE(std::filesystem::exists(target));
  {
    OutputDirectory out(target);
    write_text_atomically(out.file("b.txt"), "b");
    EXPECT_EQ(out.commit(), std::vector<std::string>{"b.txt"});
  }
  EXPECT_TRUE(std::filesystem::exists(target / "b.txt"));
  EXPECT_TRUE(std::filesystem::exists(target / kOutputMarker));
  {
    OutputDirectory out(target);  // a tightfit folder now: accepted
    write_text_atomically(out.file("c.txt"), "c");
    write_text_atomically(out.file("b.txt"), "new b");
    out.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(target / "c.txt"));
  std::ifstream b(target / "b.txt");
  std::string text;
  std::getline(b, text);
  EXPECT_EQ(text, "new b");  // replaced; nothing else removed
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(target)) ++entries;
  EXPECT_EQ(entries, 3u);  // b.txt, c.txt, the marker: no staging folder left
  std::filesystem::remove_all(target);
}

TEST(OutputDirectory, RefusesFoldersTightfitDidNotMakeUnlessForced) {
  const auto target = std::filesystem::temp_directory_path() / "tightfit_outdir_user";
  std::filesystem::remove_all(target);
  std::filesystem::create_directories(target);
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
  EXPECT_TRUE(std::filesystem::exists(target / "thesis.tex"));
  EXPECT_TRUE(std::filesystem::exists(target / "result.json"));
  // A folder holding a tightfit state.json (an earlier version's run) is a tightfit folder.
  const auto old_run = std::filesystem::temp_directory_path() / "tightfit_outdir_old_run";
  std::filesystem::remove_all(old_run);
  std::filesystem::create_directories(old_run);
  write_text_atomically(old_run / "state.json",
                        R"({"command": "simulate", "format": "tightfit-run-state"})");
  EXPECT_TRUE(is_tightfit_folder(old_run));
  write_text_atomically(old_run / "state.json", R"({"format": "something else"})");
  EXPECT_FALSE(is_tightfit_folder(old_run));
  // A killed run's staging folder alone does not make a folder foreign.
  const auto killed = std::filesystem::temp_directory_path() / "tightfit_outdir_killed";
  std::filesystem::remove_all(killed);
  std::filesystem::create_directories(killed / ".tightfit-staging.123.0");
  EXPECT_TRUE(is_tightfit_folder(killed));
  std::filesystem::remove_all(killed);
  // A file is not a folder; "dir/." is the folder itself.
  EXPECT_THROW(OutputDirectory(target / "thesis.tex"), InputError);
  {
    OutputDirectory out(target / ".", true);
    write_text_atomically(out.file("dot.txt"), "d");
    out.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(target / "dot.txt"));
  std::filesystem::remove_all(target);
  std::filesystem::remove_all(old_run);
}

}  // namespace tightfit::test::output_directory_test
