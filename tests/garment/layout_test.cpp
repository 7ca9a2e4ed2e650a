#include "tightfit/garment/layout.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <fstream>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::layout_test {

LayoutSpec spec_from(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  JsonFields f(j, "layout.json", "");
  return parse_layout_spec(f, "");
}

/// A closed cylinder of radius 0.05 m, y in [0, 0.4], with the sleeve region y ∈ [0.05, 0.35].
const char* kSleeve = R"({
  "region": [{"name": "bottom", "point": [0, 0.05, 0], "normal": [0, 1, 0]},
             {"name": "top", "point": [0, 0.35, 0], "normal": [0, -1, 0]}],
  "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0.1]}],
  "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
  "pinned": [{"name": "cuff", "on_plane": "bottom"}, {"name": "top", "nearest": [0.05, 0.36, 0]}]
})";

std::string expect_input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(Layout, SleeveOnCylinderHasTwoDiscPanelsTwoSeamsAndPinnedCuffs) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const Layout layout = layout_from_rules(body, spec_from(kSleeve));
  ASSERT_EQ(layout.panels.size(), 2u);
  ASSERT_EQ(layout.seams.size(), 2u);
  for (const auto& panel : layout.panels) {
    // seam, open, seam, open around each panel.
    ASSERT_EQ(panel.segments.size(), 4u);
    int seams = 0, pinned = 0;
    for (const auto& s : panel.segments) {
      seams += s.seam >= 0;
      pinned += s.pin >= 0;
    }
    EXPECT_EQ(seams, 2);
    EXPECT_EQ(pinned, 2);
  }
  // Cut vertices lie exactly on the planes; seams run along the divider.
  for (const auto& seam : layout.seams) {
    EXPECT_EQ(seam.vertices.front() != seam.vertices.back(), true);
    for (int v : seam.vertices) {
      const Vec3 x = layout.surface.vertices.row(v);
      EXPECT_NEAR(Vec3(1, 0, 0.1).normalized().dot(x), 0.0, 1e-12);
      EXPECT_GE(x.y(), 0.05 - 1e-12);
      EXPECT_LE(x.y(), 0.35 + 1e-12);
    }
    const Vec3 a = layout.surface.vertices.row(seam.vertices.front());
    const Vec3 b = layout.surface.vertices.row(seam.vertices.back());
    EXPECT_NEAR(std::abs(a.y() - b.y()), 0.3, 1e-12);
  }
  // Total area: the side of the 32-gon prism between the planes.
  double area = 0;
  for (int f = 0; f < layout.surface.num_faces(); ++f) {
    const Vec3 a = layout.surface.vertices.row(layout.surface.faces(f, 0));
    const Vec3 b = layout.surface.vertices.row(layout.surface.faces(f, 1));
    const Vec3 c = layout.surface.vertices.row(layout.surface.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  EXPECT_NEAR(area, 32 * 2 * 0.05 * std::sin(test::kPi / 32) * 0.3, 1e-12);
}

TEST(Layout, ReportsGapsAndOverlapsBetweenRulePanels) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  auto j = nlohmann::json::parse(kSleeve);
  j["panels"] = nlohmann::json::parse(R"([{"name": "front", "sides": ["+side"]}])");
  JsonFields f1(j, "gap.json", "");
  const std::string gap =
      expect_input_error([&] { layout_from_rules(body, parse_layout_spec(f1, "")); });
  EXPECT_NE(gap.find("gap.json: /panels: a gap"), std::string::npos) << gap;
  j["panels"] = nlohmann::json::parse(
      R"([{"name": "all", "sides": []}, {"name": "front", "sides": ["+side"]}])");
  JsonFields f2(j, "overlap.json", "");
  const std::string overlap =
      expect_input_error([&] { layout_from_rules(body, parse_layout_spec(f2, "")); });
  EXPECT_NE(overlap.find("overlap"), std::string::npos) << overlap;
  EXPECT_NE(overlap.find("\"all\" and \"front\""), std::string::npos) << overlap;
}

TEST(Layout, AStrayPartLeftByAGrazingDividerJoinsItsNeighbour) {
  // The divider x = 0.0499 grazes the first cylinder (radius 0.05 at x = 0): panel "p"
  // (x > 0.0499) is the second cylinder and a sliver of the first, which joins "q".
  const std::string text = R"({
    "region": [{"name": "top", "point": [0, 0.35, 0], "normal": "down"}],
    "dividers": [{"name": "d", "point": [0.0499, 0, 0], "normal": "left"}],
    "panels": [{"name": "p", "sides": ["+d"]}, {"name": "q", "sides": ["-d"]}]})";
  const Layout layout = layout_from_rules(test::two_cylinders(), spec_from(text));
  ASSERT_EQ(layout.panels.size(), 2u);
  ASSERT_EQ(layout.warnings.size(), 1u);
  EXPECT_NE(layout.warnings[0].find("panel \"p\" has a stray part of "), std::string::npos)
      << layout.warnings[0];
  EXPECT_NE(layout.warnings[0].find("it joins panel \"q\""), std::string::npos)
      << layout.warnings[0];
  for (int v : layout.panels[0].surface_vertex) EXPECT_GT(layout.surface.vertices(v, 0), 0.2);
  for (int v : layout.panels[1].surface_vertex) EXPECT_LT(layout.surface.vertices(v, 0), 0.1);

  // With stray parts kept (fraction 0) the panel falls apart.
  auto j = nlohmann::json::parse(text);
  j["stray_part_fraction"] = 0;
  try {
    layout_from_rules(test::two_cylinders(), spec_from(j.dump()));
    ADD_FAILURE() << "a panel in two parts accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("panel \"p\" is not a disc: it falls apart"),
              std::string::npos)
        << e.what();
  }
}

TEST(Layout, SeamsBetweenTheSamePanelsAreNumberedFromTheTopDown) {
  // The mask's halves meet along three seams (the nostril and mouth notches split the
  // midline): "left/right" is the highest, then "#2", "#3", on any head.
  std::ifstream in(std::string(TIGHTFIT_SOURCE_DIR) + "/examples/optimize_mask_pressure.json");
  const nlohmann::json scene = nlohmann::json::parse(in);
  JsonFields f(scene["garment"]["layout"], "mask.json", "/garment/layout");
  const LayoutSpec spec = parse_layout_spec(f, "");
  const Layout layout = layout_from_rules(
      read_tri_mesh(std::string(TIGHTFIT_DATA_DIR) + "/bodies/mh_head_neutral.obj"), spec);
  std::vector<std::pair<std::string, double>> seams;
  for (const LayoutSeam& seam : layout.seams) {
    double y = 0.0;
    for (int v : seam.vertices) y += layout.surface.vertices(v, 1);
    seams.emplace_back(seam.name, y / static_cast<double>(seam.vertices.size()));
  }
  std::sort(seams.begin(), seams.end());
  ASSERT_EQ(seams.size(), 3u);
  EXPECT_EQ(seams[0].first, "left/right");
  EXPECT_EQ(seams[1].first, "left/right#2");
  EXPECT_EQ(seams[2].first, "left/right#3");
  EXPECT_GT(seams[0].second, seams[1].second);
  EXPECT_GT(seams[1].second, seams[2].second);
}

TEST(Layout, RejectsPanelsThatAreNotDiscs) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  // One panel all around the cylinder: a band with two boundary loops.
  auto j = nlohmann::json::parse(kSleeve);
  j["panels"] = nlohmann::json::parse(R"([{"name": "tube"}])");
  JsonFields f(j, "tube.json", "");
  const std::string tube =
      expect_input_error([&] { layout_from_rules(body, parse_layout_spec(f, "")); });
  EXPECT_NE(
      tube.find("tube.json: /panels/0: panel \"tube\" is not a disc: it has 2 boundary loops"),
      std::string::npos)
      << tube;
  // A group layout whose "front" panel falls apart into two parts.
  const Layout sleeve = layout_from_rules(body, spec_from(kSleeve));
  std::vector<int> groups = sleeve.face_panel;
  for (int t = 0; t < sleeve.surface.num_faces(); ++t) {
    const double y = (sleeve.surface.vertices.row(sleeve.surface.faces(t, 0)) +
                      sleeve.surface.vertices.row(sleeve.surface.faces(t, 1)) +
                      sleeve.surface.vertices.row(sleeve.surface.faces(t, 2)))
                         .y() /
                     3.0;
    if (y > 0.15 && y < 0.2) groups[t] = 1;  // a band around the middle goes to "back"
  }
  auto m = nlohmann::json::parse(R"({"mesh": "parts.obj"})");
  JsonFields g(m, "parts.json", "");
  const LayoutSpec mesh_spec = parse_layout_spec(g, "");
  const std::string parts = expect_input_error([&] {
    layout_from_groups(sleeve.surface, groups, {"front", "back"}, mesh_spec, "parts.obj");
  });
  EXPECT_NE(parts.find("panel \"front\" is not a disc: it falls apart into separate parts"),
            std::string::npos)
      << parts;
}

TEST(Layout, RejectsClosedSeamsAndEmptyPanels) {
  const TriMesh sphere = test::geodesic_sphere(0.1, 6);
  const std::string closed = expect_input_error([&] {
    layout_from_rules(sphere, spec_from(R"({
      "dividers": [{"name": "equator", "point": [0, 0.01, 0], "normal": [0, 1, 0]}],
      "panels": [{"name": "top", "sides": ["+equator"]}, {"name": "bottom", "sides": ["-equator"]}]})"));
  });
  EXPECT_NE(closed.find("closed loop"), std::string::npos) << closed;
  const std::string empty = expect_input_error([&] {
    layout_from_rules(sphere, spec_from(R"({
      "dividers": [{"name": "far", "point": [0, 1, 0], "normal": [0, 1, 0]}],
      "panels": [{"name": "ghost", "sides": ["+far"]}, {"name": "all", "sides": ["-far"]}]})"));
  });
  EXPECT_NE(empty.find("panel \"ghost\" is empty"), std::string::npos) << empty;
  const std::string whole = expect_input_error(
      [&] { layout_from_rules(sphere, spec_from(R"({"panels": [{"name": "all"}]})")); });
  EXPECT_NE(whole.find("panel \"all\" is not a disc: it is closed"), std::string::npos) << whole;
}

TEST(Layout, RejectsPinnedBoundariesThatDoNotExist) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  auto j = nlohmann::json::parse(kSleeve);
  j["region"].push_back(
      nlohmann::json::parse(R"({"name": "far", "point": [0, 2, 0], "normal": [0, -1, 0]})"));
  j["pinned"] = nlohmann::json::parse(R"([{"name": "hem", "on_plane": "far"}])");
  JsonFields f(j, "pin.json", "");
  const std::string missing =
      expect_input_error([&] { layout_from_rules(body, parse_layout_spec(f, "")); });
  EXPECT_NE(missing.find("pin.json: /pinned/0: pinned boundary \"hem\" does not exist"),
            std::string::npos)
      << missing;
  j = nlohmann::json::parse(kSleeve);
  j["pinned"] =
      nlohmann::json::parse(R"([{"name": "hem", "nearest": [0, 1, 0], "max_distance": 0.1}])");
  JsonFields g(j, "pin.json", "");
  const std::string far =
      expect_input_error([&] { layout_from_rules(body, parse_layout_spec(g, "")); });
  EXPECT_NE(far.find("does not exist: the nearest open boundary is"), std::string::npos) << far;
  // A closed garment has no open boundary to pin.
  const TriMesh sphere = test::geodesic_sphere(0.1, 4);
  const std::string closed = expect_input_error([&] {
    layout_from_rules(sphere, spec_from(R"({
      "dividers": [{"name": "a", "point": [0, 0, 0], "normal": [1, 0, 0]},
                   {"name": "b", "point": [0, 0, 0], "normal": [0, 1, 0]}],
      "panels": [{"name": "p", "sides": ["+a"]}, {"name": "q", "sides": ["-a", "+b"]}, {"name": "r", "sides": ["-a", "-b"]}],
      "pinned": [{"name": "hem", "nearest": [0, 0, 0]}]})"));
  });
  EXPECT_NE(closed.find("the garment has no open boundary"), std::string::npos) << closed;
}

TEST(Layout, GroupLayoutMatchesRuleLayoutAndReportsGapsAndOverlaps) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const Layout rules = layout_from_rules(body, spec_from(kSleeve));
  auto j = nlohmann::json::parse(kSleeve);
  j.erase("region");
  j.erase("dividers");
  j.erase("panels");
  j["mesh"] = "unused.obj";
  j["pinned"] = nlohmann::json::parse(
      R"([{"name": "cuff", "on_plane": {"point": [0, 0.05, 0], "normal": [0, 1, 0]}},
          {"name": "top", "nearest": [0.05, 0.36, 0]}])");
  JsonFields f(j, "mesh.json", "");
  const LayoutSpec spec = parse_layout_spec(f, "");
  std::vector<std::string> names;
  for (const auto& p : rules.panels) names.push_back(p.name);
  const Layout groups =
      layout_from_groups(rules.surface, rules.face_panel, names, spec, "sleeve.obj");
  ASSERT_EQ(groups.panels.size(), rules.panels.size());
  ASSERT_EQ(groups.seams.size(), rules.seams.size());
  for (size_t p = 0; p < rules.panels.size(); ++p) {
    EXPECT_EQ(groups.panels[p].name, rules.panels[p].name);
    EXPECT_EQ(groups.panels[p].mesh.num_faces(), rules.panels[p].mesh.num_faces());
    ASSERT_EQ(groups.panels[p].segments.size(), rules.panels[p].segments.size());
    for (size_t s = 0; s < rules.panels[p].segments.size(); ++s) {
      EXPECT_EQ(groups.panels[p].segments[s].count, rules.panels[p].segments[s].count);
      EXPECT_EQ(groups.panels[p].segments[s].pin, rules.panels[p].segments[s].pin);
    }
  }
  // Faces in no group, the same face in two groups.
  std::vector<int> gaps = rules.face_panel;
  gaps[5] = -1;
  const std::string gap =
      expect_input_error([&] { layout_from_groups(rules.surface, gaps, names, spec, "g.obj"); });
  EXPECT_NE(gap.find("g.obj: a gap: 1 faces belong to no panel"), std::string::npos) << gap;
  TriMesh doubled = rules.surface;
  doubled.faces.conservativeResize(doubled.faces.rows() + 1, 3);
  doubled.faces.row(doubled.faces.rows() - 1) = doubled.faces.row(0);
  std::vector<int> doubled_groups = rules.face_panel;
  doubled_groups.push_back(1 - rules.face_panel[0]);
  const std::string overlap = expect_input_error(
      [&] { layout_from_groups(doubled, doubled_groups, names, spec, "o.obj"); });
  EXPECT_NE(overlap.find("o.obj: an overlap"), std::string::npos) << overlap;
  // Panels whose boundaries run side by side without sharing vertices (a sloppy export).
  TriMesh apart = rules.surface;
  std::vector<int> moved(apart.num_vertices(), -1);
  for (int t = 0; t < apart.num_faces(); ++t) {
    if (rules.face_panel[t] != 1) continue;
    for (int c = 0; c < 3; ++c) {
      int& v = moved[apart.faces(t, c)];
      if (v < 0) {
        v = apart.num_vertices();
        apart.vertices.conservativeResize(v + 1, 3);
        apart.vertices.row(v) = rules.surface.vertices.row(apart.faces(t, c)) * (1.0 + 2e-5);
      }
      apart.faces(t, c) = v;
    }
  }
  const std::string apart_error = expect_input_error(
      [&] { layout_from_groups(apart, rules.face_panel, names, spec, "a.obj"); });
  EXPECT_NE(apart_error.find("a.obj: a gap between panels"), std::string::npos) << apart_error;
}

}  // namespace tightfit::layout_test
