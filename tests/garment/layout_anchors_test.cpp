#include "tightfit/garment/layout_anchors.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/layout.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::layout_anchors_test {

LayoutSpec anchored_spec(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  JsonFields f(j, "layout.json", "");
  return parse_layout_spec(f, "");
}

std::string anchor_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// A leg of two bones along the y axis of the test cylinder (radius 0.05 m, y ∈ [0, 0.4]),
/// and a bone beside it pointing along x.
std::map<std::string, BoneSegment> leg_skeleton() {
  std::map<std::string, BoneSegment> s;
  s["thigh"] = BoneSegment{"thigh", "", Vec3(0, 0.4, 0), Vec3(0, 0.2, 0)};
  s["shin"] = BoneSegment{"shin", "thigh", Vec3(0, 0.2, 0), Vec3(0, 0.0, 0)};
  s["toe"] = BoneSegment{"toe", "shin", Vec3(0, -0.2, 0), Vec3(0.1, -0.2, 0)};
  return s;
}

/// The sleeve of layout_test.cpp with its planes anchored on leg_skeleton().
const char* kAnchoredSleeve = R"({
  "region": [{"name": "bottom", "point": {"bone": "shin", "at": 0.75}, "normal": "-along_bone"},
             {"name": "top", "point": {"bone": "thigh", "at": 0.25}, "normal": {"along_bone": "thigh"}}],
  "dividers": [{"name": "side", "point": {"bone": "shin", "at": 0.5}, "normal": "left"}],
  "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
  "pinned": [{"name": "cuff", "on_plane": "bottom"},
             {"name": "hem", "on_plane": {"point": {"bone": "thigh", "at": 0.25}, "normal": "up"}}]
})";

TEST(LayoutAnchorSpec, ParsesBoneAnchorsBodyAxesAndBoneRegions) {
  const LayoutSpec spec = anchored_spec(R"({
    "description": "anchored",
    "region": [{"name": "leg", "bones": ["upperleg01.L", "upperleg02.L"]},
               {"name": "knee", "point": {"bone": "lowerleg01.L", "at": 0.5}, "normal": "-along_bone"}],
    "dividers": [{"name": "front", "point": [0, 0, 0.01], "normal": "front"},
                 {"name": "side", "point": {"bone": "root", "at": 0}, "normal": {"along_bone": "pelvis.L", "reversed": true}}],
    "panels": [{"name": "a", "sides": ["+front"]}, {"name": "b", "sides": ["-front"]}],
    "pinned": [{"name": "hem", "on_plane": {"point": {"bone": "foot.L", "at": 1}, "normal": "down"}}]})");
  ASSERT_EQ(spec.region.size(), 2u);
  EXPECT_TRUE(spec.region[0].is_bone_region());
  EXPECT_EQ(spec.region[0].bones, (std::vector<std::string>{"upperleg01.L", "upperleg02.L"}));
  EXPECT_TRUE(spec.region[0].needs_rig());
  ASSERT_TRUE(spec.region[1].anchor.has_value());
  EXPECT_EQ(spec.region[1].anchor->bone, "lowerleg01.L");
  EXPECT_EQ(spec.region[1].anchor->at, 0.5);
  ASSERT_TRUE(spec.region[1].along_bone.has_value());
  EXPECT_EQ(spec.region[1].along_bone->bone, "lowerleg01.L");
  EXPECT_EQ(spec.region[1].along_bone->sign, -1.0);
  EXPECT_FALSE(spec.dividers[0].needs_rig());
  EXPECT_EQ(spec.dividers[0].normal, Vec3::UnitZ());
  EXPECT_EQ(spec.dividers[1].along_bone->bone, "pelvis.L");
  EXPECT_EQ(spec.dividers[1].along_bone->sign, -1.0);
  EXPECT_EQ(spec.pins[0].plane.anchor->bone, "foot.L");
  EXPECT_EQ(spec.pins[0].plane.normal, -Vec3::UnitY());
  EXPECT_EQ(spec.first_rig_use(), "/region/0");
  EXPECT_EQ(anchored_spec(R"({"panels": [{"name": "all"}]})").first_rig_use(), "");
}

TEST(LayoutAnchorSpec, NamesTheJsonPathOfMistakes) {
  const auto error_of = [](const std::string& text) {
    return anchor_error([&] { anchored_spec(text); });
  };
  EXPECT_EQ(
      error_of(R"({"region": [{"name": "r", "point": {"bone": "shin", "at": 1.5}, "normal": "up"}],
                         "panels": [{"name": "a"}]})"),
      "layout.json: /region/0/point/at: must lie in [0, 1] (a fraction of the bone from its head "
      "to its tail)");
  EXPECT_EQ(error_of(R"({"region": [{"name": "r", "point": [0, 0, 0], "normal": "sideways"}],
                         "panels": [{"name": "a"}]})"),
            "layout.json: /region/0/normal: expected [x, y, z], a body axis (left, right, up, "
            "down, front, back), "
            "\"along_bone\" or \"-along_bone\", got \"sideways\"");
  EXPECT_NE(error_of(R"({"region": [{"name": "r", "point": [0, 0, 0], "normal": "along_bone"}],
                         "panels": [{"name": "a"}]})")
                .find("/region/0/normal: \"along_bone\" needs a bone anchor as \"point\""),
            std::string::npos);
  EXPECT_NE(
      error_of(
          R"({"dividers": [{"name": "d", "bones": ["shin"], "normal": "up"}], "panels": [{"name": "a"}]})")
          .find("layout.json: /dividers/0/normal: not allowed in a bone region"),
      std::string::npos);
  EXPECT_EQ(error_of(R"({"dividers": [{"name": "d", "bones": []}], "panels": [{"name": "a"}]})"),
            "layout.json: /dividers/0/bones: expected a non-empty array of bone names");
  EXPECT_EQ(
      error_of(
          R"({"dividers": [{"name": "d", "bones": ["shin", "shin"]}], "panels": [{"name": "a"}]})"),
      "layout.json: /dividers/0/bones/1: bone \"shin\" listed twice");
  EXPECT_NE(
      error_of(
          R"({"panels": [{"name": "a"}], "pinned": [{"name": "p", "on_plane": {"bones": ["shin"]}}]})")
          .find("/pinned/0/on_plane/bones: a pin's plane cannot be a bone region"),
      std::string::npos);
  EXPECT_EQ(
      error_of(
          R"({"region": [{"name": "r", "point": {"bone": "shin", "at": 0.5, "of": 1}, "normal": "up"}],
                         "panels": [{"name": "a"}]})"),
      "layout.json: /region/0/point/of: unknown key \"of\"");
}

TEST(LayoutAnchors, PlanesAtAFractionOfABonePassThroughThatPointOfTheBone) {
  const auto skeleton = leg_skeleton();
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const LayoutSpec spec =
      resolve_layout_anchors(anchored_spec(kAnchoredSleeve), body, {&skeleton, nullptr, "rig"});
  EXPECT_EQ(spec.first_rig_use(), "");
  // bottom: 3/4 down the shin (head y = 0.2, tail y = 0), normal tail → head (+y).
  EXPECT_LT((spec.region[0].point - Vec3(0, 0.05, 0)).norm(), 1e-15);
  EXPECT_LT((spec.region[0].normal - Vec3::UnitY()).norm(), 1e-15);
  // top: a quarter down the thigh (y = 0.35), normal along the thigh (−y).
  EXPECT_LT((spec.region[1].point - Vec3(0, 0.35, 0)).norm(), 1e-15);
  EXPECT_LT((spec.region[1].normal + Vec3::UnitY()).norm(), 1e-15);
  // side: the shin's midpoint, the body's left (+x).
  EXPECT_LT((spec.dividers[0].point - Vec3(0, 0.1, 0)).norm(), 1e-15);
  EXPECT_EQ(spec.dividers[0].normal, Vec3::UnitX());
  EXPECT_LT((spec.pins[1].plane.point - Vec3(0, 0.35, 0)).norm(), 1e-15);

  // The resolved spec lays out like the absolute sleeve: the cuff on y = 0.05.
  const Layout layout = layout_from_rules(body, spec);
  ASSERT_EQ(layout.panels.size(), 2u);
  EXPECT_EQ(layout.seams.size(), 2u);
  int cuff_edges = 0;
  for (const auto& panel : layout.panels)
    for (const auto& s : panel.segments) {
      if (s.pin != 0) continue;
      for (int i = 0; i <= s.count; ++i) {
        const int v = panel.boundary[(s.first + i) % panel.boundary.size()];
        EXPECT_NEAR(panel.mesh.vertices(v, 1), 0.05, 1e-12);
      }
      cuff_edges += s.count;
    }
  EXPECT_EQ(cuff_edges, 32);
}

TEST(LayoutAnchors, UnknownBonesMissingSkeletonsAndPlanesMissingTheBodyAreErrors) {
  const auto skeleton = leg_skeleton();
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const LayoutRig rig{&skeleton, nullptr, "legs.joints.json"};
  auto text = nlohmann::json::parse(kAnchoredSleeve);
  text["dividers"][0]["point"]["bone"] = "shim";
  const std::string unknown =
      anchor_error([&] { resolve_layout_anchors(anchored_spec(text.dump()), body, rig); });
  EXPECT_EQ(unknown,
            "layout.json: /dividers/0/point/bone: unknown bone \"shim\" (not in the skeleton of "
            "legs.joints.json); did you mean \"shin\"?");
  text = nlohmann::json::parse(kAnchoredSleeve);
  text["region"][1]["normal"]["along_bone"] = "calf";
  EXPECT_EQ(anchor_error([&] { resolve_layout_anchors(anchored_spec(text.dump()), body, rig); }),
            "layout.json: /region/1/normal: unknown bone \"calf\" (not in the skeleton of "
            "legs.joints.json)");

  const std::string no_skeleton = anchor_error(
      [&] { resolve_layout_anchors(anchored_spec(kAnchoredSleeve), body, LayoutRig{}); });
  EXPECT_NE(no_skeleton.find(
                "layout.json: /region/0/point/bone: bone \"shin\": the layout is anchored on the "
                "skeleton, but no skeleton is given"),
            std::string::npos)
      << no_skeleton;

  // The toe lies below the body: a plane through it across the leg misses the body.
  text = nlohmann::json::parse(kAnchoredSleeve);
  text["region"][0]["point"] = nlohmann::json::parse(R"({"bone": "toe", "at": 0.5})");
  text["region"][0]["normal"] = "up";
  const std::string misses =
      anchor_error([&] { resolve_layout_anchors(anchored_spec(text.dump()), body, rig); });
  EXPECT_NE(
      misses.find(
          "layout.json: /region/0: region plane \"bottom\" misses the body: it does not cross the "
          "body surface, which lies on its + side, 0.2 to 0.6 m from it"),
      std::string::npos)
      << misses;
  // So does an absolute divider beside it.
  text = nlohmann::json::parse(kAnchoredSleeve);
  text["dividers"][0]["point"] = nlohmann::json::parse("[0.2, 0, 0]");
  const std::string beside =
      anchor_error([&] { resolve_layout_anchors(anchored_spec(text.dump()), body, rig); });
  EXPECT_NE(beside.find("layout.json: /dividers/0: divider \"side\" misses the body"),
            std::string::npos)
      << beside;
}

TEST(LayoutAnchors, ANormalAcrossTwoBonesIsTheNormalOfTheirPlane) {
  const auto skeleton = leg_skeleton();
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const LayoutRig rig{&skeleton, nullptr, "legs.joints.json"};
  auto text = nlohmann::json::parse(kAnchoredSleeve);
  // shin (−y) × toe (+x) = +z.
  text["dividers"][0]["normal"] = nlohmann::json::parse(R"({"across_bones": ["shin", "toe"]})");
  EXPECT_LT((resolve_layout_anchors(anchored_spec(text.dump()), body, rig).dividers[0].normal -
             Vec3::UnitZ())
                .norm(),
            1e-15);
  text["dividers"][0]["normal"]["reversed"] = true;
  EXPECT_LT((resolve_layout_anchors(anchored_spec(text.dump()), body, rig).dividers[0].normal +
             Vec3::UnitZ())
                .norm(),
            1e-15);
  text["dividers"][0]["normal"] = nlohmann::json::parse(R"({"across_bones": ["thigh", "shin"]})");
  EXPECT_EQ(anchor_error([&] { resolve_layout_anchors(anchored_spec(text.dump()), body, rig); }),
            "layout.json: /dividers/0/normal: bones \"thigh\" and \"shin\" are parallel: they span "
            "no plane");
  text["dividers"][0]["normal"] = nlohmann::json::parse(R"({"across_bones": ["shin"]})");
  EXPECT_EQ(anchor_error([&] { anchored_spec(text.dump()); }),
            "layout.json: /dividers/0/normal/across_bones: expected two bone names");
}

TEST(LayoutAnchors, ALocalPlaneCutsOnlyAlongItsLoopNearestItsPoint) {
  // Two closed cylinders side by side that the plane y = 0.1 crosses both: the local
  // region plane, whose point is on the first, cuts only the first.
  const TriMesh two = test::two_cylinders();
  const std::string text = R"({
    "region": [{"name": "cuff", "point": [0, 0.1, 0], "normal": "up", "local": true}],
    "dividers": [{"name": "side", "point": [0.15, 0, 0], "normal": "left"},
                 {"name": "front", "point": [0, 0, 0], "normal": "front"},
                 {"name": "middle", "point": [0, 0.2, 0], "normal": "up"}],
    "panels": [{"name": "a_front", "sides": ["-side", "+front"]}, {"name": "a_back", "sides": ["-side", "-front"]},
               {"name": "b_front_top", "sides": ["+side", "+front", "+middle"]},
               {"name": "b_back_top", "sides": ["+side", "-front", "+middle"]},
               {"name": "b_front_bottom", "sides": ["+side", "+front", "-middle"]},
               {"name": "b_back_bottom", "sides": ["+side", "-front", "-middle"]}]
  })";
  const LayoutSpec spec = resolve_layout_anchors(anchored_spec(text), two, LayoutRig{});
  ASSERT_EQ(spec.region[0].field.size(), static_cast<size_t>(two.num_vertices()));
  const Layout layout = layout_from_rules(two, spec);
  double lowest_a = 1.0, lowest_b = 1.0;
  for (const auto& panel : layout.panels)
    for (int v : panel.surface_vertex)
      (panel.name[0] == 'a' ? lowest_a : lowest_b) =
          std::min(panel.name[0] == 'a' ? lowest_a : lowest_b, layout.surface.vertices(v, 1));
  EXPECT_NEAR(lowest_a, 0.1, 1e-12);  // cut at the plane
  EXPECT_LT(lowest_b, 1e-12);         // the other cylinder, whole down to its bottom cap
}

/// Skin weights on the test cylinder: "upper" rises linearly from 0 at y = 0.1125 m to
/// 1 at y = 0.3125 m (½ at y = 0.2125, half-way between two rings), "lower" = 1 − upper.
SkinWeights ramp_weights(const TriMesh& body) {
  SkinWeights w;
  w.vertices = body.vertices;
  w.faces = body.faces;
  w.source = "ramp.mhw";
  for (int v = 0; v < body.num_vertices(); ++v) {
    const double upper = std::clamp((body.vertices(v, 1) - 0.1125) / 0.2, 0.0, 1.0);
    if (upper > 0.0) w.bones["upper"].emplace_back(v, upper);
    if (upper < 1.0) w.bones["lower"].emplace_back(v, 1.0 - upper);
  }
  return w;
}

TEST(LayoutBoneRegions, CutAlongTheHalfIsoLineOfTheSkinWeights) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 17);
  const SkinWeights weights = ramp_weights(body);
  const LayoutSpec spec = resolve_layout_anchors(anchored_spec(R"({
    "region": [{"name": "bottom", "point": [0, 0.05, 0], "normal": "up"},
               {"name": "top", "point": [0, 0.35, 0], "normal": "down"}],
    "dividers": [{"name": "upper", "bones": ["upper"]},
                 {"name": "side", "point": [0, 0, 0], "normal": "left"}],
    "panels": [{"name": "upper_front", "sides": ["+upper", "+side"]}, {"name": "upper_back", "sides": ["+upper", "-side"]},
               {"name": "lower_front", "sides": ["-upper", "+side"]}, {"name": "lower_back", "sides": ["-upper", "-side"]}]})"),
                                                 body, {nullptr, &weights, "ramp"});
  ASSERT_EQ(spec.dividers[0].field.size(), static_cast<size_t>(body.num_vertices()));
  const Layout layout = layout_from_rules(body, spec);
  ASSERT_EQ(layout.panels.size(), 4u);
  EXPECT_EQ(layout.seams.size(), 6u);
  // The seams between upper and lower panels run on the iso-line y = 0.2125 (the weights
  // are linear in y, so is their interpolant along every edge), with a new vertex on
  // every one of the 32 vertical edges it crosses plus the two on the side divider.
  std::set<int> iso;
  for (const auto& seam : layout.seams) {
    const bool across = (layout.panels[seam.panel_a].name.starts_with("upper")) !=
                        (layout.panels[seam.panel_b].name.starts_with("upper"));
    if (!across) continue;
    for (int v : seam.vertices) {
      EXPECT_NEAR(layout.surface.vertices(v, 1), 0.2125, 1e-12);
      iso.insert(v);
    }
  }
  EXPECT_GE(iso.size(), 32u);

  // As a region plane, a bone region keeps the surface the bones dominate, and its
  // iso-line can be pinned; unknown bones and bones that dominate nothing are errors.
  const LayoutSpec upper_only = resolve_layout_anchors(anchored_spec(R"({
    "region": [{"name": "thigh", "bones": ["upper"]}, {"name": "top", "point": [0, 0.35, 0], "normal": "down"}],
    "dividers": [{"name": "side", "point": [0, 0, 0], "normal": "left"}],
    "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
    "pinned": [{"name": "hem", "on_plane": "thigh"}]})"),
                                                       body, {nullptr, &weights, "ramp"});
  const Layout thigh = layout_from_rules(body, upper_only);
  int hem_edges = 0;
  for (const auto& panel : thigh.panels)
    for (const auto& s : panel.segments)
      if (s.pin == 0) {
        hem_edges += s.count;
        for (int i = 0; i <= s.count; ++i)
          EXPECT_NEAR(panel.mesh.vertices(panel.boundary[(s.first + i) % panel.boundary.size()], 1),
                      0.2125, 1e-12);
      }
  EXPECT_GE(hem_edges, 32);

  const std::string unknown = anchor_error([&] {
    resolve_layout_anchors(
        anchored_spec(
            R"({"region": [{"name": "r", "bones": ["lower", "uper"]}], "panels": [{"name": "a"}]})"),
        body, {nullptr, &weights, "ramp"});
  });
  EXPECT_EQ(
      unknown,
      "layout.json: /region/0/bones/1: unknown bone \"uper\" (no skin weights for it in ramp.mhw); "
      "did you mean \"upper\"?");
  SkinWeights all_lower = weights;
  all_lower.bones.erase("upper");
  all_lower.bones["lower"].clear();
  for (int v = 0; v < body.num_vertices(); ++v) all_lower.bones["lower"].emplace_back(v, 1.0);
  all_lower.bones["upper"] = {};
  const std::string none = anchor_error([&] {
    resolve_layout_anchors(
        anchored_spec(
            R"({"region": [{"name": "r", "bones": ["upper"]}], "panels": [{"name": "a"}]})"),
        body, {nullptr, &all_lower, "ramp"});
  });
  EXPECT_NE(none.find("layout.json: /region/0: region plane \"r\" misses the body: the bones upper "
                      "dominate no part "
                      "of the body surface"),
            std::string::npos)
      << none;
  const std::string no_weights = anchor_error([&] {
    resolve_layout_anchors(
        anchored_spec(
            R"({"region": [{"name": "r", "bones": ["upper"]}], "panels": [{"name": "a"}]})"),
        body, LayoutRig{});
  });
  EXPECT_NE(no_weights.find("layout.json: /region/0/bones: bone region \"r\" needs skin weights"),
            std::string::npos)
      << no_weights;
}

/// One layout file on bodies of the MakeHuman rig: three full bodies of different build
/// and size with their own joints (vertex i of each is the rig's vertex i), and the legs
/// body cropped and renumbered from mh_male_regular, with that body's rig (weights carried
/// by position).
class LayoutAnchorTransfer : public ::testing::Test {
 protected:
  struct RigBody {
    std::string name;
    TriMesh surface;
    std::map<std::string, BoneSegment> skeleton;
    SkinWeights weights;
  };

  static void SetUpTestSuite() {
    const std::string data = TIGHTFIT_DATA_DIR;
    bodies_ = new std::vector<RigBody>;
    for (const auto& [body, rig] :
         std::vector<std::pair<std::string, std::string>>{{"mh_male_regular", "mh_male_regular"},
                                                          {"mh_male_athletic", "mh_male_athletic"},
                                                          {"mh_child", "mh_child"},
                                                          {"mh_legs_male", "mh_male_regular"}}) {
      RigBody b;
      b.name = body;
      b.surface = read_tri_mesh(data + "/bodies/" + body + ".obj");
      b.skeleton = read_skeleton(data + "/rig/" + rig + ".joints.json");
      b.weights =
          read_skin_weights(data + "/bodies/" + rig + ".obj", data + "/rig/default_weights.mhw");
      bodies_->push_back(std::move(b));
    }
  }
  static void TearDownTestSuite() { delete bodies_; }

  static std::vector<RigBody>* bodies_;
};

std::vector<LayoutAnchorTransfer::RigBody>* LayoutAnchorTransfer::bodies_ = nullptr;

/// Surface vertices of the layout's boundary segments pinned by pin `pin`.
std::vector<int> pinned_vertices(const Layout& layout, int pin) {
  std::vector<int> out;
  for (const auto& panel : layout.panels)
    for (const auto& s : panel.segments)
      if (s.seam < 0 && s.pin == pin)
        for (int i = 0; i <= s.count; ++i)
          out.push_back(
              panel.surface_vertex[panel.boundary[(s.first + i) % panel.boundary.size()]]);
  return out;
}

TEST_F(LayoutAnchorTransfer, OneLayoutFileLaysOutEveryBodyOfTheRigAtItsOwnJoints) {
  const LayoutSpec spec = read_layout_spec(std::string(TIGHTFIT_SOURCE_DIR) +
                                           "/examples/layouts/left_leg_anchored.json");
  std::vector<std::string> first_seams;
  std::vector<double> cuff_heights;
  for (const RigBody& body : *bodies_) {
    SCOPED_TRACE(body.name);
    const LayoutSpec absolute =
        resolve_layout_anchors(spec, body.surface, {&body.skeleton, &body.weights, body.name});
    // The cuff plane lies 3/4 down this body's own lower shin, across it.
    const BoneSegment& shin = body.skeleton.at("lowerleg02.L");
    const LayoutPlane& cuff = absolute.region[1];
    EXPECT_LT((cuff.point - (shin.head + 0.75 * (shin.tail - shin.head))).norm(), 1e-12);
    EXPECT_LT((cuff.normal + (shin.tail - shin.head).normalized()).norm(), 1e-12);
    cuff_heights.push_back(cuff.point.y());

    const Layout layout = layout_from_rules(body.surface, absolute);
    std::vector<std::string> panels, seams;
    for (const auto& p : layout.panels) panels.push_back(p.name);
    for (const auto& s : layout.seams) seams.push_back(s.name);
    EXPECT_EQ(panels, (std::vector<std::string>{"thigh_front", "thigh_back", "lower_leg_front",
                                                "lower_leg_back"}));
    EXPECT_EQ(seams.size(), 6u);
    if (first_seams.empty()) first_seams = seams;
    EXPECT_EQ(seams, first_seams);
    EXPECT_EQ(layout.pin_names, (std::vector<std::string>{"top", "cuff"}));
    // Both open boundaries are pinned: the top (the leg bones' iso-line) and the cuff, on
    // this body's cuff plane.
    EXPECT_FALSE(pinned_vertices(layout, 0).empty());
    const std::vector<int> cuff_vertices = pinned_vertices(layout, 1);
    EXPECT_FALSE(cuff_vertices.empty());
    for (int v : cuff_vertices)
      EXPECT_LT(std::abs(cuff.distance(layout.surface.vertices.row(v).transpose())), 1e-9);
  }
  // The taller athletic man's cuff is higher, the child's lower; the legs body shares the
  // regular man's joints.
  EXPECT_GT(cuff_heights[1], cuff_heights[0] + 0.005);
  EXPECT_LT(cuff_heights[2], cuff_heights[0] - 0.01);
  EXPECT_EQ(cuff_heights[3], cuff_heights[0]);
}

TEST_F(LayoutAnchorTransfer, TheTwelvePieceWetsuitLaysOutOnEveryFullBodyWithLocalCuffs) {
  const LayoutSpec spec =
      read_layout_spec(std::string(TIGHTFIT_SOURCE_DIR) + "/examples/layouts/wetsuit_12.json");
  for (size_t b = 0; b < 3; ++b) {  // the full bodies
    const RigBody& body = (*bodies_)[b];
    SCOPED_TRACE(body.name);
    const LayoutSpec absolute =
        resolve_layout_anchors(spec, body.surface, {&body.skeleton, &body.weights, body.name});
    const Layout layout = layout_from_rules(body.surface, absolute);
    ASSERT_EQ(layout.panels.size(), 12u);
    EXPECT_EQ(layout.pin_names,
              (std::vector<std::string>{"neckline", "cuff_L", "cuff_R", "ankle_L", "ankle_R"}));
    // Each cuff lies on its own plane around its own wrist or ankle; none is empty.
    const std::vector<std::pair<std::string, double>> cuffs = {{"neck01", 0.5},
                                                               {"lowerarm02.L", 0.7},
                                                               {"lowerarm02.R", 0.7},
                                                               {"lowerleg02.L", 0.7},
                                                               {"lowerleg02.R", 0.7}};
    for (int pin = 0; pin < 5; ++pin) {
      const LayoutPlane& plane = absolute.region[static_cast<size_t>(pin)];
      const BoneSegment& bone = body.skeleton.at(cuffs[static_cast<size_t>(pin)].first);
      const Vec3 anchor =
          bone.head + cuffs[static_cast<size_t>(pin)].second * (bone.tail - bone.head);
      const std::vector<int> ring = pinned_vertices(layout, pin);
      ASSERT_FALSE(ring.empty()) << layout.pin_names[static_cast<size_t>(pin)];
      for (int v : ring) {
        const Vec3 x = layout.surface.vertices.row(v).transpose();
        EXPECT_LT(std::abs(plane.normal.dot(x - anchor)), 1e-9);
        EXPECT_LT((x - anchor).norm(), 0.12);  // around this limb, not another one
      }
    }
    // The wrist planes pass behind the feet in the A-pose; being local, they leave the
    // legs whole down to the ankle cuffs.
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& panel : layout.panels)
      if (panel.name.rfind("leg_", 0) == 0)
        for (int v : panel.surface_vertex) lowest = std::min(lowest, layout.surface.vertices(v, 1));
    const BoneSegment& shin = body.skeleton.at("lowerleg02.L");
    EXPECT_LT(lowest, (shin.head + 0.7 * (shin.tail - shin.head)).y() + 0.03);
  }
}

}  // namespace tightfit::layout_anchors_test
