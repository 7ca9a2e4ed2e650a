#include "tightfit/common/input_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit::input_file_test {

namespace fs = std::filesystem;

std::string error_of(const fs::path& path, std::uintmax_t max_bytes = kMaxInputBytes) {
  try {
    read_input_file(path, max_bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, OnlyRegularFilesAreReadAndTheirSizeIsCheckedFirst) {
  const fs::path dir = fs::temp_directory_path() / ("tightfit_input_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "body.obj") << "v 0 0 0\n";
  EXPECT_EQ(read_input_file(dir / "body.obj"), "v 0 0 0\n");
  // A FIFO is refused at once: opening it does not wait for a writer.
  ASSERT_EQ(::mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
  EXPECT_NE(error_of(dir / "fifo.obj").find("is a FIFO (named pipe), not a regular file"),
            std::string::npos);
  // A link to a device is followed and refused; it is never read until memory runs out.
  fs::create_symlink("/dev/zero", dir / "zero.obj");
  EXPECT_NE(error_of(dir / "zero.obj").find("is a device"), std::string::npos);
  fs::create_directories(dir / "folder.obj");
  EXPECT_NE(error_of(dir / "folder.obj").find("is a folder"), std::string::npos);
  EXPECT_NE(error_of(dir / "missing.obj").find("file does not exist"), std::string::npos);
  EXPECT_NE(error_of(dir / "body.obj", 4).find("more than the"), std::string::npos);
  fs::remove_all(dir);
}

TEST(InputFile, RecordsWhatWasReadWithAHashOfItsBytes) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_input_record_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::uint64_t before = input_reads();
  std::ofstream(dir / "a.json") << "{}";
  read_input_file(dir / "a.json");
  auto read = input_files_read(before);
  ASSERT_EQ(read.size(), 1u);
  const std::string key = fs::weakly_canonical(dir / "a.json").string();
  EXPECT_EQ(read.at(key), content_hash("{}"));
  std::ofstream(dir / "a.json") << "{\"a\": 1}";
  read_input_file(dir / "a.json");
  EXPECT_EQ(input_files_read(before).at(key), content_hash("{\"a\": 1}"));
  EXPECT_NE(content_hash("{}"), content_hash("{ }"));
  EXPECT_TRUE(input_files_read(input_reads()).empty());
  fs::remove_all(dir);
}

}  // namespace tightfit::input_file_test
