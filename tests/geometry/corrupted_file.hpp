#pragma once
/// Random corruption of files, to check that readers fail only with InputError.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit::test {

/// Reads `original`, writes `trials` corrupted copies next to it (same file name
/// suffix) and calls `read` on each: it may succeed or throw InputError, nothing else.
/// Corruptions: overwrite a few bytes (with digits, signs, blanks, newlines or any
/// byte), delete a range, or truncate.
inline void expect_only_input_errors(const std::filesystem::path& original, int trials,
                                     const std::function<void(const std::filesystem::path&)>& read,
                                     const std::string& suffix) {
  std::ifstream in(original, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(data.empty());
  std::mt19937 rng(12345);
  const std::string alphabet = "0123456789-+. \n\teE/#";
  for (int trial = 0; trial < trials; ++trial) {
    std::string bad = data;
    auto pos = [&] { return std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng); };
    switch (trial % 4) {
      case 0:
      case 1:
        for (int k = 0; k < 1 + trial % 3; ++k)
          bad[pos()] =
              trial % 2 ? alphabet[rng() % alphabet.size()] : static_cast<char>(rng() & 0xff);
        break;
      case 2: {
        const std::size_t at = pos();
        bad.erase(at, std::uniform_int_distribution<std::size_t>(1, 16)(rng));
        break;
      }
      default:
        bad.resize(pos());
        break;
    }
    const auto path = original.parent_path() / ("corrupt" + std::to_string(trial) + suffix);
    std::ofstream(path, std::ios::binary) << bad;
    try {
      read(path);
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << " of " << original << ": " << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace tightfit::test
