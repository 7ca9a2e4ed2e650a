#pragma once
/// A fresh temporary directory for one test, removed with its contents afterwards.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

namespace tightfit::test {

class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("tightfit_" + std::string(info ? info->name() : "test") + "_" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Path of a file in tests/geometry/data.
inline std::filesystem::path geometry_data(const std::string& name) {
  return std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "tests/geometry/data" / name;
}

}  // namespace tightfit::test
