/// The inputs fuzzing found (and hostile inputs found by hand) for each reader, read
/// again on every test run: tests/fuzz_regressions/READER/FILE, READER a name of
/// fuzz/readers.hpp. A reader must succeed or throw InputError, never anything else
/// (the sanitizer and memcheck builds also catch what would crash).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../../fuzz/readers.hpp"

namespace tightfit::fuzz_regression_test {

TEST(FuzzRegressions, EveryReaderAnswersHostileFilesWithAnInputError) {
  const std::filesystem::path root =
      std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "tests/fuzz_regressions";
  ASSERT_TRUE(std::filesystem::is_directory(root)) << root;
  int files = 0;
  for (const auto& dir : std::filesystem::directory_iterator(root)) {
    const std::string name = dir.path().filename().string();
    const auto reader = fuzz::readers().find(name);
    ASSERT_NE(reader, fuzz::readers().end())
        << "no reader called " << name << " (fuzz/readers.hpp)";
    for (const auto& file : std::filesystem::directory_iterator(dir.path())) {
      ++files;
      try {
        reader->second.read(file.path());
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.path().filename().string()), std::string::npos)
            << "the error does not name the file: " << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << file.path() << ": " << e.what() << " (not an InputError)";
      }
    }
  }
  EXPECT_GE(files, 5);
}

}  // namespace tightfit::fuzz_regression_test
