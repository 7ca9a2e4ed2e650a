#include "tightfit/garment/layout_spec.hpp"

#include <gtest/gtest.h>

#include "tightfit/garment/pattern_options.hpp"

namespace tightfit::layout_spec_test {

LayoutSpec parse(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  JsonFields f(j, "layout.json", "/layout");
  return parse_layout_spec(f, "/specs");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LayoutSpec, ParsesRulesAndMeshLayouts) {
  const LayoutSpec rules = parse(R"({
    "region": [{"name": "waist", "point": [0, 1, 0], "normal": [0, -2, 0]}],
    "dividers": [{"name": "mid", "point": [0, 0, 0], "normal": [1, 0, 0]}],
    "panels": [{"name": "left", "sides": ["+mid"]}, {"name": "right", "sides": ["-mid"]}],
    "pinned": [{"name": "band", "on_plane": "waist"}, {"name": "cuff", "nearest": [0, 0.1, 0], "max_distance": 0.05},
               {"name": "hem", "on_plane": {"point": [0, 0.2, 0], "normal": [0, 1, 0]}}],
    "seam_tolerance": 0.08})");
  EXPECT_FALSE(rules.is_mesh_layout());
  ASSERT_EQ(rules.region.size(), 1u);
  EXPECT_EQ(rules.region[0].normal, Vec3(0, -1, 0));
  EXPECT_DOUBLE_EQ(rules.region[0].distance(Vec3(0, 0.5, 0)), 0.5);
  ASSERT_EQ(rules.panels.size(), 2u);
  EXPECT_EQ(rules.panels[1].sides, (std::vector<std::pair<int, int>>{{0, -1}}));
  ASSERT_EQ(rules.pins.size(), 3u);
  EXPECT_EQ(rules.pins[0].kind, PinRule::Kind::kOnRegionPlane);
  EXPECT_EQ(rules.pins[1].kind, PinRule::Kind::kNearest);
  EXPECT_EQ(rules.pins[1].max_distance, 0.05);
  EXPECT_EQ(rules.pins[2].kind, PinRule::Kind::kOnPlane);
  EXPECT_EQ(rules.pins[0].source_path, "/layout/pinned/0");
  EXPECT_EQ(rules.seam_tolerance, 0.08);

  const LayoutSpec mesh =
      parse(R"({"mesh": "panels.obj", "pinned": [{"name": "x", "nearest": [0, 0, 0]}]})");
  EXPECT_TRUE(mesh.is_mesh_layout());
  EXPECT_EQ(mesh.mesh_file, "/specs/panels.obj");
  EXPECT_EQ(mesh.seam_tolerance, 0.05);
}

TEST(LayoutSpec, NamesTheJsonPathOfMistakes) {
  EXPECT_EQ(error_of(R"({"panels": [{"name": "a", "sides": ["+nope"]}]})"),
            "layout.json: /layout/panels/0/sides/0: unknown divider \"nope\"");
  EXPECT_EQ(error_of(R"({"dividers": [{"name": "d", "point": [0,0,0], "normal": [1,0,0]}],
                         "panels": [{"name": "a", "sides": ["d"]}]})"),
            "layout.json: /layout/panels/0/sides/0: expected \"+name\" or \"-name\", got \"d\"");
  EXPECT_EQ(
      error_of(R"({"panels": [{"name": "a"}], "pinned": [{"name": "p", "on_plane": "waist"}]})"),
      "layout.json: /layout/pinned/0/on_plane: unknown region plane \"waist\"");
  EXPECT_EQ(error_of(R"({"panels": [{"name": "a"}], "pinned": [{"name": "p"}]})"),
            "layout.json: /layout/pinned/0: give exactly one of \"on_plane\" and \"nearest\"");
  EXPECT_EQ(error_of(R"({"panels": [{"name": "a"}, {"name": "a"}]})"),
            "layout.json: /layout/panels/1/name: duplicate panel name \"a\"");
  EXPECT_EQ(error_of(R"({"panels": []})"),
            "layout.json: /layout/panels: at least one panel is needed");
  EXPECT_EQ(error_of(R"({"mesh": "x.obj", "panels": [{"name": "a"}]})"),
            "layout.json: /layout/panels: not allowed together with \"mesh\"");
  EXPECT_EQ(error_of(R"({"panels": [{"name": "a"}], "extra": 1})"),
            "layout.json: /layout/extra: unknown key \"extra\"");
  EXPECT_EQ(
      error_of(
          R"({"region": [{"name": "r", "point": [0,0,0], "normal": [0,0,0]}], "panels": [{"name": "a"}]})"),
      "layout.json: /layout/region/0/normal: the normal must not be zero");
}

TEST(PatternOptions, ParsesScalesAndGrain) {
  const auto j =
      nlohmann::json::parse(R"({"edge_length": 0.015, "scale": [0.95, 0.8], "grain": [0, 2, 0],
                                           "piece_scale": {"front": [1.0, 0.7]}, "smoothing_iterations": 3})");
  JsonFields f(j, "scene.json", "/pattern");
  const PatternOptions o = parse_pattern_options(f);
  EXPECT_EQ(o.edge_length, 0.015);
  EXPECT_EQ(o.scale_of("back").across, 0.8);
  EXPECT_EQ(o.scale_of("front").across, 0.7);
  EXPECT_EQ(*o.grain, Vec3(0, 1, 0));
  EXPECT_EQ(o.smoothing_iterations, 3);
  const auto bad = nlohmann::json::parse(R"({"scale": [0.9, -1]})");
  JsonFields g(bad, "scene.json", "/pattern");
  try {
    parse_pattern_options(g);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: /pattern/scale: scale factors must be positive");
  }
}

}  // namespace tightfit::layout_spec_test
