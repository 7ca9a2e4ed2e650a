#include "tightfit/patterns/json.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit::pattern_json_test {

void expect_same_pattern(const Pattern& a, const Pattern& b) {
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (size_t p = 0; p < a.pieces.size(); ++p) {
    const PatternPiece& x = a.pieces[p];
    const PatternPiece& y = b.pieces[p];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.rest, y.rest);  // bit-exact: doubles round-trip through JSON
    EXPECT_EQ(x.triangles, y.triangles);
    EXPECT_EQ(x.boundary, y.boundary);
    EXPECT_EQ(x.corners, y.corners);
    EXPECT_EQ(x.grain, y.grain);
  }
  ASSERT_EQ(a.seams.size(), b.seams.size());
  for (size_t s = 0; s < a.seams.size(); ++s) {
    EXPECT_EQ(a.seams[s].name, b.seams[s].name);
    EXPECT_EQ(a.seams[s].a.piece, b.seams[s].a.piece);
    EXPECT_EQ(a.seams[s].a.vertices, b.seams[s].a.vertices);
    EXPECT_EQ(a.seams[s].b.piece, b.seams[s].b.piece);
    EXPECT_EQ(a.seams[s].b.vertices, b.seams[s].b.vertices);
  }
  ASSERT_EQ(a.pinned.size(), b.pinned.size());
  for (size_t i = 0; i < a.pinned.size(); ++i) {
    EXPECT_EQ(a.pinned[i].name, b.pinned[i].name);
    EXPECT_EQ(a.pinned[i].piece, b.pinned[i].piece);
    EXPECT_EQ(a.pinned[i].vertices, b.pinned[i].vertices);
  }
}

TEST(PatternJson, RoundTripKeepsPiecesAndSeams) {
  const auto dir = test::scratch_dir("json_round_trip");
  Pattern pattern = test::test_pattern();
  pattern.pieces[0].rest(3, 0) += 1e-13;  // a value that does not print short
  pattern.pieces[1].name = "back \xC3\xA9l\xC3\xA9ment \"quoted\"";
  write_pieces_json(pattern, {}, dir / "pieces.json");
  const Pattern read = read_pieces_json(dir / "pieces.json");
  expect_same_pattern(pattern, read);
  // Writing what was read gives the same file.
  write_pieces_json(read, {}, dir / "again.json");
  EXPECT_EQ(read_json_file((dir / "pieces.json").string()),
            read_json_file((dir / "again.json").string()));
}

TEST(PatternJson, CarriesOutlinesNotchesAndSeamCorrespondences) {
  const auto dir = test::scratch_dir("json_content");
  const Pattern pattern = test::test_pattern();
  PatternExportOptions options;
  options.seam_allowances["side_left"] = 0.015;
  write_pieces_json(pattern, options, dir / "pieces.json");
  const nlohmann::json j = read_json_file((dir / "pieces.json").string());
  EXPECT_EQ(j["format"], "tightfit-pieces");
  EXPECT_EQ(j["units"]["rest"], "m");
  EXPECT_EQ(j["units"]["outlines"], "mm");
  const auto& front = j["pieces"][0];
  ASSERT_EQ(front["sew_line_mm"].size(), pattern.pieces[0].boundary.size());
  EXPECT_DOUBLE_EQ(front["sew_line_mm"][6][0].get<double>(), 300.0);  // vertex 6 = (0.3, 0) m
  EXPECT_GT(front["cut_line_mm"].size(), 3u);
  EXPECT_DOUBLE_EQ(front["allowance_mm"][20].get<double>(), 15.0);
  size_t notches = 0;
  for (const auto& piece : j["pieces"]) notches += piece["notches_mm"].size();
  EXPECT_EQ(notches, 2u * (5 + 5 + 3));
  const auto& seam = j["seams"][2];
  EXPECT_EQ(seam["name"], "sleeve_hem");
  EXPECT_EQ(seam["a"]["piece_name"], "sleeve");
  EXPECT_EQ(seam["b"]["piece_name"], "back");
  EXPECT_EQ(seam["b"]["vertices"], nlohmann::json({20, 19, 18, 17, 16, 15, 14}));
  EXPECT_EQ(j["pinned"][0]["name"], "waist");
}

void expect_read_error(const std::filesystem::path& file, const std::string& text,
                       const std::string& fragment) {
  {
    std::ofstream out(file);
    out << text;
  }
  try {
    read_pieces_json(file);
    ADD_FAILURE() << "expected InputError containing '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(PatternJson, MalformedFilesAreInputErrors) {
  const auto dir = test::scratch_dir("json_errors");
  write_pieces_json(test::test_pattern(), {}, dir / "good.json");
  const nlohmann::json good = read_json_file((dir / "good.json").string());
  const auto bad = dir / "bad.json";
  expect_read_error(bad, "{", "invalid JSON");
  {
    nlohmann::json j = good;
    j["pieces"][1]["triangles"][0] = {1, 2};
    expect_read_error(bad, j.dump(), "/pieces/1/triangles/0");
  }
  {
    nlohmann::json j = good;
    j["seams"][0]["b"]["vertices"].erase(0);
    expect_read_error(bad, j.dump(), "different vertex counts");
  }
  {
    nlohmann::json j = good;
    j["pieces"][0]["boundary"][2] = 1000;
    expect_read_error(bad, j.dump(), "out of range");
  }
  {
    nlohmann::json j = good;
    j["pieces"][0]["colour"] = "red";
    expect_read_error(bad, j.dump(), "unknown key \"colour\"");
  }
  {
    nlohmann::json j = good;
    j["format"] = "something";
    expect_read_error(bad, j.dump(), "/format");
  }
}

}  // namespace tightfit::pattern_json_test
