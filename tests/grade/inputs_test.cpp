/// The inputs of `tightfit grade` without running it: the bodies file, each body's
/// scene made from the design (paths that still resolve), the fingerprint of a body's
/// inputs, and the nest of several sizes (aligned pieces, one spot per piece).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "support/sphere_mesh.hpp"
#include "support/test_pieces.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/grade/bodies.hpp"
#include "tightfit/grade/scene.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"
#include "tightfit/patterns/nest.hpp"
#include "tightfit/scene/skeleton_fit.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit {
namespace grade_inputs_test {

namespace fs = std::filesystem;

class GradeInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_grade_inputs_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const fs::path& name, const std::string& text) {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  /// The error message of `f()`, or "" when it does not throw InputError.
  template <class F>
  static std::string input_error(F f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(GradeInputs, TheBodiesFileResolvesPathsAndDefaultsTheRigMeshToTheMesh) {
  const fs::path file = write("pop/bodies.json", R"({"bodies": [
      {"name": "regular", "mesh": "m/regular.obj", "joints": "/abs/regular.joints.json"},
      {"name": "legs-1.0", "mesh": "legs.obj", "joints": "j.json", "rig_mesh": "full.obj"}]})");
  const std::vector<GradeBody> bodies = read_grade_bodies(file);
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].mesh, dir_ / "pop/m/regular.obj");
  EXPECT_EQ(bodies[0].joints, fs::path("/abs/regular.joints.json"));
  EXPECT_EQ(bodies[0].rig_mesh, bodies[0].mesh);
  EXPECT_EQ(bodies[1].rig_mesh, dir_ / "pop/full.obj");
}

TEST_F(GradeInputs, BadBodiesFilesNameTheFileAndTheEntry) {
  const std::string f = (dir_ / "b.json").string();
  auto error = [&](const std::string& text) {
    write("b.json", text);
    return input_error([&] { read_grade_bodies(f); });
  };
  EXPECT_EQ(error(R"({"bodies": []})"),
            f + ": /bodies: expected a non-empty array of bodies {\"name\", \"mesh\", \"joints\"}");
  EXPECT_NE(error(R"({"bodies": [{"name": "a/b", "mesh": "x", "joints": "y"}]})")
                .find(f + ": /bodies/0/name: \"a/b\" is not a body name"),
            std::string::npos);
  EXPECT_NE(error(R"({"bodies": [{"name": "a", "mesh": "x"}]})").find(f + ": /bodies/0"),
            std::string::npos);
  EXPECT_NE(
      error(R"({"bodies": [{"name": "a", "mesh": "x", "joints": "y", "scale": 2}]})").find("scale"),
      std::string::npos);
  EXPECT_NE(error(R"({"bodies": [{"name": "a", "mesh": "x", "joints": "y"},
                                 {"name": "a", "mesh": "z", "joints": "y"}]})")
                .find(f + ": /bodies/1/name: two bodies are named \"a\" (/bodies/0 too)"),
            std::string::npos);
}

TEST_F(GradeInputs, ABodysSceneReplacesBodyAndRigAndKeepsEveryOtherPathResolving) {
  const fs::path design_file = write("designs/design.json", R"({
    "body": {"mesh": "bodies/design_body.obj", "edge_length": 0.02,
             "core": {"skeleton": "rig/s.joints.json", "bones": ["a"]}},
    "garment": {"layout": "layouts/leg.json", "pattern": {"edge_length": 0.02}},
    "rig": {"mesh": "bodies/design_body.obj", "weights": "rig/w.mhw", "joints": "rig/design.joints.json"},
    "pressure": {"rig": {"mesh": "bodies/design_body.obj", "weights": "rig/w.mhw"}},
    "fabric": "fabrics/knit.json",
    "optimize": {"objectives": {"shape": {"weight": 1, "target": "/abs/target.obj"}}}})");
  const GradeDesign design = read_grade_design(design_file);
  const GradeBody body{"tall", dir_ / "pop/tall.obj", dir_ / "pop/tall.joints.json",
                       dir_ / "pop/tall_full.obj"};
  const fs::path folder = dir_ / "out/bodies/tall";
  const nlohmann::json scene = grade_body_scene(design, body, folder);
  auto resolved = [&](const nlohmann::json& v) {
    return (folder / v.get<std::string>()).lexically_normal();
  };
  EXPECT_EQ(scene["body"]["mesh"], "../../../pop/tall.obj");
  EXPECT_EQ(resolved(scene["rig"]["joints"]), dir_ / "pop/tall.joints.json");
  EXPECT_EQ(resolved(scene["rig"]["mesh"]), dir_ / "pop/tall_full.obj");
  EXPECT_EQ(resolved(scene["pressure"]["rig"]["mesh"]), dir_ / "pop/tall_full.obj");
  EXPECT_EQ(resolved(scene["rig"]["weights"]), dir_ / "designs/rig/w.mhw");
  EXPECT_EQ(resolved(scene["garment"]["layout"]), dir_ / "designs/layouts/leg.json");
  EXPECT_EQ(resolved(scene["body"]["core"]["skeleton"]), dir_ / "designs/rig/s.joints.json");
  EXPECT_EQ(resolved(scene["fabric"]), dir_ / "designs/fabrics/knit.json");
  EXPECT_EQ(scene["optimize"]["objectives"]["shape"]["target"], "/abs/target.obj");
  EXPECT_EQ(scene["body"]["edge_length"], 0.02);
  EXPECT_EQ(scene["garment"]["pattern"], design.document["garment"]["pattern"]);
}

TEST_F(GradeInputs, ADesignWithoutOptimizeBodyMeshOrRigIsRefused) {
  const std::string f = (dir_ / "d.json").string();
  auto error = [&](const std::string& text) {
    write("d.json", text);
    return input_error([&] { read_grade_design(f); });
  };
  EXPECT_NE(
      error(R"({"body": {"mesh": "b.obj"}, "rig": {"mesh": "b", "weights": "w", "joints": "j"}})")
          .find("\"optimize\""),
      std::string::npos);
  EXPECT_NE(
      error(R"({"body": {"generator": "cylinder"}, "optimize": {}, "rig": {}})").find("/body"),
      std::string::npos);
  // Without a body, each body is its mesh with the default settings.
  write("d.json", R"({"optimize": {"objectives": {"stretch": {"weight": 1}}},
                       "rig": {"mesh": "b", "weights": "w", "joints": "j"}})");
  const GradeDesign bare = read_grade_design(f);
  const nlohmann::json scene =
      grade_body_scene(bare, {"x", dir_ / "x.obj", dir_ / "x.json", dir_ / "x.obj"}, dir_);
  EXPECT_EQ(scene["body"], (nlohmann::json{{"mesh", "x.obj"}}));
  EXPECT_NE(error(R"({"body": {"mesh": "b.obj"}, "optimize": {}})").find("\"rig\""),
            std::string::npos);
  EXPECT_NE(
      error(R"({"body": {"mesh": "b.obj"}, "optimize": {}, "rig": {"mesh": "b", "weights": "w"}})")
          .find("/rig/joints"),
      std::string::npos);
  // The "optimize" section is the same for every body: checked before any body runs.
  EXPECT_EQ(error(R"({"optimize": {"objectives": {"stretch": {"weight": 1}}, "max_iteration": 3},
                     "rig": {"mesh": "b", "weights": "w", "joints": "j"}})")
                .rfind(f + ": /optimize", 0),
            0u);
}

TEST_F(GradeInputs, TheFingerprintChangesWithTheSceneTheFilesItNamesAndTheExtra) {
  write("body.obj", "v 0 0 0\n");
  const nlohmann::json scene = {{"body", {{"mesh", "body.obj"}}},
                                {"fabric", {{"thickness", 1e-4}}}};
  const std::string base = grade_fingerprint(scene, dir_, "n=2");
  EXPECT_EQ(base.size(), 16u);
  EXPECT_EQ(grade_fingerprint(scene, dir_, "n=2"), base);
  EXPECT_NE(grade_fingerprint(scene, dir_, "n=3"), base);
  nlohmann::json other = scene;
  other["fabric"]["thickness"] = 2e-4;
  EXPECT_NE(grade_fingerprint(other, dir_, "n=2"), base);
  write("body.obj", "v 0 0 1\n");
  EXPECT_NE(grade_fingerprint(scene, dir_, "n=2"), base);
}

TEST_F(GradeInputs, TheNestTurnsGrainsUpAlignsCentroidsAndPlacesEachPieceOnce) {
  // Two sizes of two pieces; the larger size's pieces are turned by 90 degrees.
  auto size = [](double scale, bool turned) {
    Pattern p;
    for (const char* name : {"front", "back"}) {
      PatternPiece piece = test::grid_piece(4, 5, 0.2 * scale, 0.3 * scale, 0.0, 1);
      piece.name = name;
      if (turned) {
        for (Eigen::Index i = 0; i < piece.rest.rows(); ++i)
          piece.rest.row(i) = Vec2(-piece.rest(i, 1), piece.rest(i, 0)).transpose();
        piece.grain = Vec2(-1.0, 0.0);
      }
      p.pieces.push_back(piece);
    }
    return p;
  };
  const Pattern small = size(1.0, false), large = size(1.2, true);
  const Nest nest = make_nest({{"S", &small}, {"L", &large}}, "");
  ASSERT_EQ(nest.pattern.pieces.size(), 4u);
  EXPECT_EQ(nest.pattern.pieces[2].name, "front/L");
  EXPECT_EQ(nest.group, (std::vector<int>{0, 1, 0, 1}));
  EXPECT_EQ(nest.size, (std::vector<int>{0, 0, 1, 1}));
  for (const PatternPiece& piece : nest.pattern.pieces) {
    EXPECT_TRUE(piece.grain.isApprox(Vec2::UnitY()));
    const Vec2 lo = piece.rest.colwise().minCoeff(), hi = piece.rest.colwise().maxCoeff();
    EXPECT_NEAR(lo.x() + hi.x(), 0.0, 1e-12) << piece.name;  // centred on the origin
    EXPECT_NEAR(lo.y() + hi.y(), 0.0, 1e-12) << piece.name;
    EXPECT_GT(hi.y() - lo.y(), hi.x() - lo.x()) << piece.name;  // the long side along the grain
  }
  PatternExportOptions options;
  options.nest_group = nest.group;
  const PatternLayout layout =
      layout_pattern(draw_pattern_pieces(nest.pattern, options, "nest"), options);
  EXPECT_TRUE(layout.offsets[0].isApprox(layout.offsets[2]));
  EXPECT_TRUE(layout.offsets[1].isApprox(layout.offsets[3]));
  EXPECT_GT((layout.offsets[0] - layout.offsets[1]).norm(), 100.0);
  const std::string error = input_error([&] { make_nest({{"S", &small}}, "side"); });
  EXPECT_EQ(error, "--nest-seam: no seam \"side\" in the pattern of S");
}

TEST_F(GradeInputs, JointsOutsideTheBodyAreAnErrorNamingTheFarthestAndTheFaceRigIsLeftOut) {
  const TriMesh ball = test::sphere_mesh(0.1, Vec3::Zero(), 0.02);
  std::map<std::string, BoneSegment> skeleton;
  skeleton["spine"] = {"spine", "", Vec3(0, -0.05, 0), Vec3(0, 0.05, 0)};
  skeleton["head"] = {"head", "spine", Vec3(0, 0.05, 0), Vec3(0, 0.2, 0)};  // crown 10 cm out
  skeleton["eye.L"] = {"eye.L", "head", Vec3(0.02, 0.15, 0.05), Vec3(0.02, 0.15, 0.2)};
  skeleton["toe"] = {"toe", "spine", Vec3(0, -0.05, 0),
                     Vec3(0, -0.105, 0)};  // 5 mm out: on the skin
  EXPECT_NO_THROW(check_joints_inside(ball, skeleton, "s.joints.json", "ball.obj"));
  skeleton["arm"] = {"arm", "spine", Vec3(0.05, 0, 0), Vec3(0.15, 0, 0)};  // 5 cm out
  skeleton["hand"] = {"hand", "arm", Vec3(0.15, 0, 0), Vec3(0.25, 0, 0)};  // 5 and 15 cm out
  const std::string error =
      input_error([&] { check_joints_inside(ball, skeleton, "s.joints.json", "ball.obj"); });
  EXPECT_EQ(
      error.rfind(
          "s.joints.json: the tail of bone \"hand\" (0.250, 0.000, 0.000) m lies 150 mm outside "
          "the body ball.obj (3 joints lie more than 10 mm outside it)",
          0),
      0u)
      << error;
}

TEST_F(GradeInputs, TheGradingExamplesMatchTheirSchemasAndEveryBodysSceneParses) {
  const fs::path source(TIGHTFIT_SOURCE_DIR);
  const fs::path bodies_file = source / "examples/grading/bodies_full.json";
  const fs::path design_file = source / "examples/grading/left_leg.json";
  auto validates = [&](const fs::path& schema, const fs::path& file) {
    const std::string cmd =
        "/usr/bin/python3 -c \"import json,sys,jsonschema; "
        "jsonschema.validate(json.load(open(sys.argv[2])), json.load(open(sys.argv[1])))\" '" +
        schema.string() + "' '" + file.string() + "'";
    return std::system(cmd.c_str()) == 0;
  };
  EXPECT_TRUE(validates(source / "schema/bodies.schema.json", bodies_file));
  EXPECT_TRUE(validates(source / "schema/scene.schema.json", design_file));
  const std::vector<GradeBody> bodies = read_grade_bodies(bodies_file);
  ASSERT_EQ(bodies.size(), 4u);
  const GradeDesign design = read_grade_design(design_file);
  const fs::path folder = dir_ / "out/bodies" / bodies[3].name;
  fs::create_directories(folder);
  const nlohmann::json scene = grade_body_scene(design, bodies[3], folder);
  std::ofstream(folder / "scene.json") << scene.dump(2);
  EXPECT_TRUE(validates(source / "schema/scene.schema.json", folder / "scene.json"));
  const SceneSpec spec = read_scene(folder / "scene.json");
  EXPECT_EQ(fs::weakly_canonical(spec.body.mesh.path),
            fs::weakly_canonical(source / "data/bodies/mh_child.obj"));
  ASSERT_TRUE(spec.rig);
}

}  // namespace grade_inputs_test
}  // namespace tightfit
