#include "tightfit/body/body_spec.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::body_spec_test {

using nlohmann::json;

std::string error_of(const json& j, const std::string& path = "") {
  try {
    parse_body_spec(j, path, TIGHTFIT_SOURCE_DIR, "spec.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BodySpec, CylinderWithDefaults) {
  const BodySpec s =
      parse_body_spec(json::parse(R"({"generator":"cylinder","radius":0.05,"length":0.3})"), "",
                      TIGHTFIT_SOURCE_DIR, "spec.json");
  EXPECT_EQ(s.source, BodySource::kCylinder);
  EXPECT_EQ(s.cylinder.radius, 0.05);
  EXPECT_EQ(s.cylinder.length, 0.3);
  EXPECT_EQ(s.cylinder.caps, CapStyle::kRound);
  EXPECT_TRUE(s.cylinder.fit_limit);
  EXPECT_NEAR(s.edge_length, default_generator_edge_length(0.05), 1e-15);
  EXPECT_EQ(s.volume.quality.max_radius_edge, 1.4);
  EXPECT_EQ(s.volume.quality.min_dihedral_deg, 12.0);
  EXPECT_NEAR(s.volume.quality.max_volume, regular_tet_volume(2.0 * s.edge_length), 1e-20);
  ASSERT_TRUE(s.volume.core.soft_tissue.has_value());
  EXPECT_EQ(*s.volume.core.soft_tissue, 0.015);
  EXPECT_TRUE(s.volume.core.bones.empty());
}

TEST(BodySpec, CropsAnchoredOnTheSkeletonAreResolvedOnTheBodysOwnOrTheRigsJoints) {
  const std::string crop =
      R"("crop": [{"point": {"bone": "lowerarm02.L", "at": 0.85}, "normal": "-along_bone", "local": true}])";
  const json own = json::parse(R"({"mesh": "data/bodies/mh_male_regular.obj",
                                   "skeleton": "data/rig/mh_male_regular.joints.json", )" +
                               crop + "}");
  const BodySpec s = parse_body_spec(own, "/body", TIGHTFIT_SOURCE_DIR, "scene.json");
  const std::map<std::string, BoneSegment> regular =
      read_skeleton(std::string(TIGHTFIT_SOURCE_DIR) + "/data/rig/mh_male_regular.joints.json");
  const BoneSegment& forearm = regular.at("lowerarm02.L");
  ASSERT_EQ(s.mesh.crop.size(), 1u);
  EXPECT_LT((s.mesh.crop[0].point - (forearm.head + 0.85 * (forearm.tail - forearm.head))).norm(),
            1e-15);
  EXPECT_LT((s.mesh.crop[0].normal + (forearm.tail - forearm.head).normalized()).norm(), 1e-15);
  EXPECT_TRUE(s.mesh.crop[0].local);

  // Without a skeleton of its own the body takes the one it is given (a scene's rig):
  // the child's forearm is elsewhere.
  const json bare = json::parse(R"({"mesh": "data/bodies/mh_child.obj", )" + crop + "}");
  const std::map<std::string, BoneSegment> child =
      read_skeleton(std::string(TIGHTFIT_SOURCE_DIR) + "/data/rig/mh_child.joints.json");
  const BodySpec c = parse_body_spec(bare, "/body", TIGHTFIT_SOURCE_DIR, "scene.json",
                                     {&child, "child.joints.json"});
  const BoneSegment& child_forearm = child.at("lowerarm02.L");
  EXPECT_LT((c.mesh.crop[0].point -
             (child_forearm.head + 0.85 * (child_forearm.tail - child_forearm.head)))
                .norm(),
            1e-15);

  EXPECT_EQ(error_of(bare, "/body"),
            "spec.json: /body/crop/0: anchored on the skeleton, but there is none: give the body a "
            "\"skeleton\" "
            "(a joints file) or the scene a \"rig\"");
  json typo = own;
  typo["crop"][0]["point"]["bone"] = "lowerarm02.l";
  EXPECT_EQ(
      error_of(typo, "/body"),
      "spec.json: /body/crop/0/point/bone: unknown bone \"lowerarm02.l\" (not in the skeleton of " +
          (std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "data/rig/mh_male_regular.joints.json")
              .string() +
          "); did you mean \"lowerarm02.L\"?");
}

TEST(BodySpec, SizesInMillimetresAndEdgesTooShortToMeshAreErrorsBeforeMeshing) {
  EXPECT_EQ(
      error_of(json::parse(R"({"generator": "cylinder", "radius": 50, "length": 0.3})"), "/body"),
      "spec.json: /body/radius: a radius of 50 m is larger than any body part: lengths are in "
      "metres "
      "(50 mm is 0.05)");
  EXPECT_EQ(
      error_of(json::parse(R"({"generator": "cylinder", "radius": 0.05, "length": 300})"), "/body"),
      "spec.json: /body/length: a length of 300 m is longer than any body: lengths are in metres "
      "(300 mm is 0.3)");
  const std::string tiny = error_of(
      json::parse(R"({"generator": "sphere", "radius": 0.1, "edge_length": 0.00005})"), "/body");
  EXPECT_NE(
      tiny.find(
          "spec.json: /body/edge_length: an edge length of 5e-05 m would mesh the sphere's surface "
          "(0.126 m²) into about 1.16e+08 triangles, more than 2e+06"),
      std::string::npos)
      << tiny;
  EXPECT_EQ(
      error_of(json::parse(R"({"generator": "sphere", "radius": 0.1, "edge_length": 0.0005})"),
               "/body"),
      "");
}

TEST(BodySpec, MeshWithCropAndBones) {
  const json j = json::parse(R"({
    "mesh": "data/bodies/mh_legs_male.obj", "edge_length": 0.02, "scale": 1.0,
    "crop": [{"point": [0, 0.5, 0], "normal": [0, 1, 0]}],
    "max_radius_edge": 1.5, "min_dihedral_deg": 10, "interior_edge_length": 0.05,
    "core": {"skeleton": "data/rig/mh_male_regular.joints.json",
             "bones": ["upperleg02.L", "upperleg02.R"], "bone_radius": 0.02}})");
  const BodySpec s = parse_body_spec(j, "/body", TIGHTFIT_SOURCE_DIR, "scene.json");
  EXPECT_EQ(s.source, BodySource::kMesh);
  EXPECT_EQ(s.mesh.path,
            std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "data/bodies/mh_legs_male.obj");
  ASSERT_EQ(s.mesh.crop.size(), 1u);
  EXPECT_EQ(s.mesh.crop[0].point, Vec3(0, 0.5, 0));
  EXPECT_EQ(s.mesh.remesh_options.edge_length, 0.02);
  EXPECT_EQ(s.mesh.remesh_options.cap_planes.size(), 1u);
  EXPECT_FALSE(s.mesh.fit_limit);
  EXPECT_EQ(s.volume.quality.max_radius_edge, 1.5);
  EXPECT_NEAR(s.volume.quality.max_volume, regular_tet_volume(0.05), 1e-20);
  EXPECT_FALSE(s.volume.core.soft_tissue.has_value());
  ASSERT_EQ(s.volume.core.bones.size(), 2u);
  EXPECT_EQ(s.volume.core.bones[1].name, "upperleg02.R");
  EXPECT_EQ(s.volume.core.bone_radius, 0.02);
  EXPECT_EQ(s.volume.core.source, "scene.json: /body/core");
}

TEST(BodySpec, ErrorsNameTheFileAndJsonPath) {
  EXPECT_EQ(error_of(json::parse(R"({"generator":"cylinder","radius":"big","length":0.3})")),
            "spec.json: /radius: expected a number, got string");
  EXPECT_EQ(error_of(json::parse(R"({"generator":"sphere","radius":0.1,"colour":1})"), "/body"),
            "spec.json: /body/colour: unknown key \"colour\"");
  EXPECT_EQ(error_of(json::parse(R"({"generator":"sphere","radius":0.1,"length":1})")),
            "spec.json: /length: unknown key \"length\"");
  EXPECT_NE(error_of(json::parse(R"({"generator":"cone","radius":0.1})"))
                .find("/generator: unknown value"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"radius":0.1})")).find("exactly one of"), std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"generator":"sphere","mesh":"x.obj","radius":0.1})"))
                .find("exactly one of"),
            std::string::npos);
  EXPECT_EQ(error_of(json::parse(R"({"generator":"sphere","radius":0.1,"edge_length":0.2})")),
            "spec.json: /edge_length: the edge length must not exceed the radius");
  EXPECT_EQ(error_of(json::parse(R"({"generator":"sphere","radius":0.1,"min_dihedral_deg":30})")),
            "spec.json: /min_dihedral_deg: expected an angle in [0, 18] degrees");
  EXPECT_EQ(
      error_of(json::parse(R"({"mesh":"x.obj","crop":[{"point":[0,0,0],"normal":[0,0,0]}]})")),
      "spec.json: /crop/0/normal: the normal must not be zero");
  EXPECT_EQ(error_of(json::parse(R"({"mesh":"x.obj","crop":[{"point":[0,0],"normal":[0,1,0]}]})")),
            "spec.json: /crop/0/point: expected an array of 3 numbers");
  EXPECT_EQ(
      error_of(json::parse(R"({"generator":"sphere","radius":0.1,"core":{"soft_tissue":-1}})")),
      "spec.json: /core/soft_tissue: expected a positive number, got -1.000000");
  EXPECT_EQ(
      error_of(json::parse(
          R"({"generator":"sphere","radius":0.1,"core":{"skeleton":"data/rig/mh_male_regular.joints.json","bones":["upperleg02.L","wing"]}})")),
      "spec.json: /core/bones/1: no bone \"wing\" in " TIGHTFIT_SOURCE_DIR
      "/data/rig/mh_male_regular.joints.json");
  EXPECT_NE(
      error_of(json::parse(R"({"generator":"sphere","radius":0.1,"core":{"bones":["root"]}})"))
          .find("go together"),
      std::string::npos);
  EXPECT_EQ(error_of(json::parse("[1, 2]")), "spec.json: /: expected an object, got array");
  EXPECT_EQ(error_of(json::parse(R"({"mesh":"x.obj","core":{"radius":0.02}})")),
            "spec.json: /core/radius: an embedded core radius needs a generator body");
  EXPECT_EQ(
      error_of(json::parse(R"({"generator":"sphere","radius":0.1,"core":{"radius":0.1}})")),
      "spec.json: /core/radius: the core radius must be positive and smaller than the body's");
}

TEST(BodySpec, BuildErrorsNameTheSpecOrTheMeshFile) {
  auto build_error = [](const json& j) {
    try {
      build_body(parse_body_spec(j, "/body", TIGHTFIT_SOURCE_DIR, "scene.json"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(build_error(json::parse(R"({"mesh":"data/bodies/missing.obj"})")).find("missing.obj"),
            std::string::npos);
  EXPECT_EQ(
      build_error(json::parse(
          R"({"mesh":"data/bodies/mh_legs_male.obj","crop":[{"point":[0,2,0],"normal":[0,1,0]}]})")),
      "scene.json: /body/crop/0: the plane removes the whole surface");
  const std::string thick = build_error(json::parse(
      R"({"generator":"sphere","radius":0.03,"edge_length":0.01,"core":{"soft_tissue":0.04}})"));
  EXPECT_EQ(thick.rfind("scene.json: /body/core: no vertex is pinned", 0), 0u) << thick;
}

}  // namespace tightfit::body_spec_test
