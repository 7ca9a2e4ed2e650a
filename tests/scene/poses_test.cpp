// The scene's "rig" and "poses", and `tightfit pose`.
#include "tightfit/scene/poses.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include <filesystem>
#include <fstream>

#include "support/cli_run.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/scene/optimization_setup.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::scene_poses_test {

namespace fs = std::filesystem;

/// A scene on the legs body with the rig, and `poses` as given.
nlohmann::json posed_scene(const nlohmann::json& poses) {
  auto j = nlohmann::json::parse(R"({
      "body": {"mesh": "data/bodies/mh_legs_male.obj", "edge_length": 0.03},
      "garment": {"cover": {}},
      "rig": {"mesh": "data/bodies/mh_male_regular.obj", "weights": "data/rig/default_weights.mhw",
              "joints": "data/rig/mh_male_regular.joints.json"}})");
  j["poses"] = poses;
  return j;
}

std::string pose_error(const nlohmann::json& scene) {
  try {
    parse_scene(scene, "scene.json", TIGHTFIT_SOURCE_DIR);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenePoses, RotationsAndBvhFramesResolveToBoneRotations) {
  const SceneSpec s = parse_scene(posed_scene(nlohmann::json::parse(R"([
      {"name": "knee", "rotations": {"lowerleg01.L": [90, 0, 0]}},
      {"name": "t-pose", "bvh": "data/rig/tpose.bvh", "frame": 0},
      {"name": "twist", "rotations": {"upperleg01.R": [0, 30, 10]}, "order": "ZYX"}])")),
                                  "scene.json", TIGHTFIT_SOURCE_DIR);
  ASSERT_TRUE(s.rig);
  EXPECT_EQ(s.rig->skinning, SkinningMethod::kDualQuaternion);
  EXPECT_TRUE(s.pressure_rig);  // bone pressure regions may use the scene's rig
  ASSERT_EQ(s.poses.size(), 3u);
  EXPECT_EQ(s.poses[0].name, "knee");
  EXPECT_LT(
      (s.poses[0].rotations.at("lowerleg01.L") - euler_rotation(Vec3(90, 0, 0), "XYZ")).norm(),
      1e-15);
  EXPECT_EQ(s.poses[0].origin, "scene.json /poses/0");
  EXPECT_GT(s.poses[1].rotations.size(), 10u);
  EXPECT_NE(s.poses[1].origin.find("tpose.bvh frame 0"), std::string::npos);
  EXPECT_LT(
      (s.poses[2].rotations.at("upperleg01.R") - euler_rotation(Vec3(0, 30, 10), "ZYX")).norm(),
      1e-15);
}

TEST(ScenePoses, BadPosesAreErrorsNamingTheJsonPathOrTheBone) {
  using nlohmann::json;
  auto one = [](const json& pose) { return pose_error(posed_scene(json::array({pose}))); };
  EXPECT_NE(one({{"name", "a"}, {"rotations", {{"kneecap.L", {1, 2, 3}}}}})
                .find("/poses/0/rotations/kneecap.L: the rig's skeleton has no bone \"kneecap.L\""),
            std::string::npos);
  EXPECT_NE(
      one({{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2}}}}}).find("expected [a, b, c]"),
      std::string::npos);
  EXPECT_NE(
      one({{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2, 1e9}}}}}).find("within ±360"),
      std::string::npos);
  EXPECT_NE(
      one({{"name", "a b"}, {"rotations", {{"lowerleg01.L", {1, 2, 3}}}}}).find("/poses/0/name"),
      std::string::npos);
  EXPECT_NE(one({{"name", "a"}}).find("either \"bvh\""), std::string::npos);
  EXPECT_NE(one({{"name", "a"}, {"bvh", "data/rig/tpose.bvh"}, {"frame", 3}})
                .find("frame 3 does not exist"),
            std::string::npos);
  EXPECT_NE(one({{"name", "a"}, {"bvh", "data/rig/missing.bvh"}}).find("missing.bvh"),
            std::string::npos);
  EXPECT_NE(one({{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2, 3}}}}, {"order", "XXY"}})
                .find("/poses/0/order"),
            std::string::npos);
  const json twice = json::array({{{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2, 3}}}}},
                                  {{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2, 3}}}}}});
  EXPECT_NE(pose_error(posed_scene(twice)).find("/poses/1/name: another pose has this name"),
            std::string::npos);
  json no_rig =
      posed_scene(json::array({{{"name", "a"}, {"rotations", {{"lowerleg01.L", {1, 2, 3}}}}}}));
  no_rig.erase("rig");
  EXPECT_NE(pose_error(no_rig).find("/poses: poses need a rig"), std::string::npos);
  json bad_rig = posed_scene(json::array());
  bad_rig["rig"]["skinning"] = "spline";
  EXPECT_NE(pose_error(bad_rig).find("/rig/skinning"), std::string::npos);
}

TEST(PoseCli, WritesEveryPosedBodyOrNothing) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_pose_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto write_scene = [&](const nlohmann::json& poses) {
    nlohmann::json j = posed_scene(poses);
    j["body"]["mesh"] = std::string(TIGHTFIT_SOURCE_DIR) + "/data/bodies/mh_legs_male.obj";
    for (const char* key : {"mesh", "weights", "joints"})
      j["rig"][key] = std::string(TIGHTFIT_SOURCE_DIR) + "/" + j["rig"][key].get<std::string>();
    std::ofstream(dir / "scene.json") << j.dump(2);
  };
  write_scene(
      nlohmann::json::parse(R"([{"name": "knee_45", "rotations": {"lowerleg01.L": [45, 0, 0]}}])"));
  const auto ok = test::run_cli("pose scene.json --out out", dir.string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  for (const char* file : {"body_neutral.obj", "body_pose_knee_45.obj", "poses.json"})
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  const auto summary = nlohmann::json::parse(test::read_text(dir / "out/poses.json"));
  EXPECT_EQ(summary["poses"][0]["name"], "knee_45");
  EXPECT_NEAR(summary["poses"][0]["volume_ratio"].get<double>(), 1.0, 0.02);
  EXPECT_GT(summary["poses"][0]["tet_volume_ratio"]["min"].get<double>(), 0.0);
  // A pose that folds the body inside out: an input error, and no new folder.
  write_scene(
      nlohmann::json::parse(R"([{"name": "folded", "rotations": {"lowerleg01.L": [170, 0, 0]}}])"));
  const auto bad = test::run_cli("pose scene.json --out out2", dir.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("pose \"folded\" inverts"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "out2"));
  fs::remove_all(dir);
}

/// Writes DIR/scene.json: the posed legs scene with one pose (or none) and the given
/// "optimize" objectives, every path absolute.
void write_optimize_scene(const fs::path& dir, const nlohmann::json& objectives, bool with_poses) {
  nlohmann::json j = posed_scene(
      nlohmann::json::parse(R"([{"name": "knee", "rotations": {"lowerleg01.L": [30, 0, 0]}}])"));
  if (!with_poses) j.erase("poses");
  j["body"]["mesh"] = std::string(TIGHTFIT_SOURCE_DIR) + "/data/bodies/mh_legs_male.obj";
  for (const char* key : {"mesh", "weights", "joints"})
    j["rig"][key] = std::string(TIGHTFIT_SOURCE_DIR) + "/" + j["rig"][key].get<std::string>();
  j["optimize"] = {{"objectives", objectives}};
  std::ofstream(dir / "scene.json") << j.dump();
}

TEST(ScenePoses, TheSlidingObjectiveNeedsPosesTheSceneHas) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_sliding_spec_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto error = [&](const nlohmann::json& sliding, bool with_poses) {
    write_optimize_scene(dir, {{"sliding", sliding}}, with_poses);
    try {
      const OptimizationScene s = read_optimization_scene((dir / "scene.json").string());
      return std::string("no error, ") + std::to_string(s.optimization.poses.bone_motions.size()) +
             " poses";
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(error({{"weight", 1}}, true), "no error, 1 poses");
  EXPECT_NE(error({{"weight", 1}, {"poses", {"knee", "hop"}}}, true)
                .find("/optimize/objectives/sliding/poses: the scene has no pose \"hop\""),
            std::string::npos);
  EXPECT_NE(error({{"weight", 1}}, false).find("asks for poses"), std::string::npos);
  EXPECT_NE(error({{"weight", 1}, {"friction", -0.3}}, true)
                .find("/optimize/objectives/sliding/friction"),
            std::string::npos);
  EXPECT_NE(
      error({{"weight", 1}, {"poses", nlohmann::json::array()}}, true).find("non-empty array"),
      std::string::npos);
  // Stretch in every pose: the scene's poses are resolved for it too.
  auto stretch = [&](const nlohmann::json& poses, bool with_poses) {
    write_optimize_scene(dir, {{"stretch", {{"weight", 1}, {"min", 1.0}, {"poses", poses}}}},
                         with_poses);
    try {
      const OptimizationScene s = read_optimization_scene((dir / "scene.json").string());
      return std::to_string(s.optimization.stretch->all_poses) + " " +
             std::to_string(s.optimization.poses.bone_motions.size());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(stretch("all", true), "1 1");
  EXPECT_EQ(stretch("neutral", true), "0 0");
  EXPECT_NE(stretch("some", true).find("/optimize/objectives/stretch/poses"), std::string::npos);
  EXPECT_NE(stretch("all", false).find("asks for poses"), std::string::npos);
  fs::remove_all(dir);
}

TEST(PoseCli, SimulateWritesTheGarmentInEveryPoseAndItsSlidingStatisticsSlow) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_pose_simulate_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string data = std::string(TIGHTFIT_SOURCE_DIR) + "/data/";
  nlohmann::json scene = {
      {"body",
       {{"mesh", data + "bodies/mh_legs_male.obj"},
        {"edge_length", 0.03},
        {"crop", nlohmann::json::parse(R"([{"point": [0, 0.33, 0], "normal": [0, 1, 0]},
                    {"point": [0, 0.68, 0], "normal": [0, -1, 0]}, {"point": [0.02, 0, 0], "normal": [1, 0, 0]}])")}}},
      {"garment", {{"cover", {{"scale", 0.95}}}}},
      {"rig",
       {{"mesh", data + "bodies/mh_male_regular.obj"},
        {"weights", data + "rig/default_weights.mhw"},
        {"joints", data + "rig/mh_male_regular.joints.json"}}},
      {"poses", nlohmann::json::parse(
                    R"([{"name": "knee_45", "rotations": {"lowerleg01.L": [45, 0, 0]}}])")}};
  std::ofstream(dir / "knee.json") << scene.dump(2);
  const auto run = test::run_cli("simulate knee.json --out out", dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(fs::exists(dir / "out/garment_pose_knee_45.ply"));
  const auto result = nlohmann::json::parse(test::read_text(dir / "out/result.json"));
  ASSERT_EQ(result["poses"].size(), 1u);
  const auto& pose = result["poses"][0];
  EXPECT_EQ(pose["name"], "knee_45");
  EXPECT_EQ(pose["friction"], 0.3);
  EXPECT_GT(pose["free_vertices"].get<int>(), 100);
  // Bending the knee under a cover that was in equilibrium standing: part of it slides.
  EXPECT_GT(pose["sliding_share"].get<double>(), 0.0);
  EXPECT_LT(pose["sliding_share"].get<double>(), 1.0);
  EXPECT_GT(pose["sliding_objective_n2"].get<double>(), 0.0);
  EXPECT_GT(pose["pressing_n_median"].get<double>(), 0.0);
  EXPECT_EQ(pose["body"]["inverted_tets"], 0);
  // The posed garment has the garment's vertices and the per-vertex forces.
  const PlyData ply = read_ply(dir / "out/garment_pose_knee_45.ply");
  const PlyData neutral = read_ply(dir / "out/garment.ply");
  EXPECT_EQ(ply.mesh.num_vertices(), neutral.mesh.num_vertices());
  ASSERT_EQ(ply.attributes.vertex_fields.size(), 3u);
  EXPECT_EQ(ply.attributes.vertex_fields[0].name, "sliding_excess_n");
  EXPECT_GT((ply.mesh.vertices - neutral.mesh.vertices).rowwise().norm().maxCoeff(), 0.05);
  // The tables per face: the neutral fit and the pose, whose bent knee stretches the
  // cover and makes part of it slide.
  auto rows = [&](const std::string& file) {
    std::vector<std::vector<std::string>> out;
    std::istringstream in(test::read_text(dir / "out" / file));
    for (std::string line; std::getline(in, line);) {
      std::vector<std::string> cells;
      std::istringstream cs(line);
      for (std::string cell; std::getline(cs, cell, ',');) cells.push_back(cell);
      out.push_back(cells);
    }
    return out;
  };
  const auto table = rows("garment.csv");
  const auto posed = rows("garment_pose_knee_45.csv");
  ASSERT_EQ(table.size(), static_cast<std::size_t>(neutral.mesh.num_faces()) + 1);
  ASSERT_EQ(posed.size(), table.size());
  EXPECT_EQ(table[0][3], "stretch_max");
  EXPECT_EQ(posed[0].back(), "sliding_excess_n");
  double most_stretch = 0.0, most_excess = 0.0;
  for (std::size_t r = 1; r < posed.size(); ++r) {
    most_stretch = std::max(most_stretch, std::stod(posed[r][3]) - std::stod(table[r][3]));
    most_excess = std::max(most_excess, std::stod(posed[r].back()));
  }
  EXPECT_GT(most_stretch, 0.05);
  EXPECT_GT(most_excess, 0.0);
  fs::remove_all(dir);
}

}  // namespace tightfit::scene_poses_test
