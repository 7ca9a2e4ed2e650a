/// No output file ever holds a NaN or an infinity: the JSON writer and the array checks
/// that every writer calls inside write_file_atomically refuse them with a SolverError
/// naming the file and where the number is, and leave no file behind.
#include "tightfit/common/finite_output.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit::finite_output_test {

namespace fs = std::filesystem;

constexpr double kOutNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kOutInf = std::numeric_limits<double>::infinity();

class FiniteOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tightfit_finite_output_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Names of the files in the folder (temporary files included).
  std::string listing() const {
    std::string names;
    for (const auto& e : fs::directory_iterator(dir_)) names += e.path().filename().string() + " ";
    return names;
  }

  fs::path dir_;
};

std::string read_output_file(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The message of the SolverError `write` throws (fails the test when it throws none).
template <class Write>
std::string finite_output_error(Write write) {
  try {
    write();
  } catch (const NonFiniteOutput& e) {
    ADD_FAILURE() << "a NonFiniteOutput escaped the writer: " << e.what();
    return e.what();
  } catch (const SolverError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SolverError";
  return {};
}

TEST_F(FiniteOutput, JsonWithANaNIsRefusedNamingTheFileAndThePathAndLeavesNoFile) {
  nlohmann::json doc = {
      {"history", nlohmann::json::array({{{"value", 1.5}}, {{"value", kOutNaN}}})},
      {"name", "run"}};
  const fs::path file = dir_ / "history.json";
  const std::string what = finite_output_error([&] { write_json_atomically(file, doc, 2); });
  EXPECT_NE(what.find(file.string() + ": not written: non-finite number (nan) at /history/1/value"),
            std::string::npos)
      << what;
  EXPECT_EQ(listing(), "");  // neither the file nor its temporary
}

TEST_F(FiniteOutput, AFileAlreadyThereStaysAsItWas) {
  const fs::path file = dir_ / "result.json";
  write_json_atomically(file, {{"objective", 0.25}}, 2);
  const std::string before = read_output_file(file);
  EXPECT_EQ(nlohmann::json::parse(before)["objective"].get<double>(), 0.25);
  const std::string what = finite_output_error([&] {
    write_json_atomically(file, {{"objective", -kOutInf}}, 2);
  });
  EXPECT_NE(what.find("(-inf) at /objective"), std::string::npos) << what;
  EXPECT_EQ(read_output_file(file), before);
  EXPECT_EQ(listing(), "result.json ");
}

TEST_F(FiniteOutput, JsonPointersEscapeKeysAndNameTheRoot) {
  std::string what = finite_output_error([&] {
    write_json_atomically(dir_ / "a.json", {{"a/b~c", {{"x", kOutInf}}}});
  });
  EXPECT_NE(what.find("(inf) at /a~1b~0c/x"), std::string::npos) << what;
  what =
      finite_output_error([&] { write_json_atomically(dir_ / "b.json", nlohmann::json(kOutNaN)); });
  EXPECT_NE(what.find("(nan) at /"), std::string::npos) << what;
  EXPECT_EQ(listing(), "");
}

TEST_F(FiniteOutput, FiniteJsonIsWrittenAsDumpedAndNullsOfNoValueStay) {
  // A null the writer puts on purpose (a statistic without data) is not a number.
  const nlohmann::json doc = {{"max", 1e308}, {"median", nullptr}, {"count", 3}};
  write_json_atomically(dir_ / "ok.json", doc, 2);
  EXPECT_EQ(read_output_file(dir_ / "ok.json"), doc.dump(2) + "\n");
}

TEST_F(FiniteOutput, ArrayChecksInsideAnyWriterNameRowAndColumn) {
  Points3 positions = Points3::Zero(4, 3);
  positions(2, 1) = kOutNaN;
  const fs::path file = dir_ / "mesh.txt";
  const std::string what = finite_output_error([&] {
    write_file_atomically(file, [&](std::ostream& out) {
      out << "a header written before the check\n";
      require_finite_matrix(positions, "the vertex positions");
    });
  });
  EXPECT_NE(what.find(file.string() + ": not written: non-finite number (nan) in the vertex "
                                      "positions, row 2, column 1"),
            std::string::npos)
      << what;
  EXPECT_EQ(listing(), "");
  const float values[] = {1.0f, 2.0f, -std::numeric_limits<float>::infinity()};
  try {
    require_finite_values(values, 3, "colours");
    ADD_FAILURE() << "no NonFiniteOutput";
  } catch (const NonFiniteOutput& e) {
    EXPECT_EQ(std::string(e.what()), "non-finite number (-inf) in colours, element 2");
  }
  EXPECT_NO_THROW(require_finite_values(values, 2, "colours"));
}

}  // namespace tightfit::finite_output_test
