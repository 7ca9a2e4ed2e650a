/// Runs the built `tightfit` (TIGHTFIT_CLI): `simulate`, `optimize` and `layout` write
/// state.json, and `tightfit export` regenerates their outputs from it without solving.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace tightfit::export_cli_test {

namespace fs = std::filesystem;

using test::CliRun;
using test::read_text;
using test::run_cli;

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(read_text(file)); }

/// The JSON embedded in a report.html.
nlohmann::json report_data(const fs::path& file) {
  const std::string html = read_text(file);
  const std::string open = "<script type=\"application/json\" id=\"tightfit-data\">";
  const auto begin = html.find(open);
  if (begin == std::string::npos) return nullptr;
  const auto start = begin + open.size();
  return nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
}

/// The JSON chunk of a .glb file.
nlohmann::json glb_json(const fs::path& file) {
  const std::string bytes = read_text(file);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

/// Same structure; numbers equal within `tol` relative to max(1, |a|).
void expect_json_near(const nlohmann::json& a, const nlohmann::json& b, double tol,
                      const std::string& path = "") {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), tol * std::max(1.0, std::abs(x))) << path;
    return;
  }
  ASSERT_EQ(a.type(), b.type()) << path;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (auto it = a.begin(); it != a.end(); ++it) {
      ASSERT_TRUE(b.contains(it.key())) << path << "/" << it.key();
      expect_json_near(it.value(), b[it.key()], tol, path + "/" + it.key());
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (size_t i = 0; i < a.size(); ++i)
      expect_json_near(a[i], b[i], tol, path + "/" + std::to_string(i));
  } else {
    EXPECT_EQ(a, b) << path;
  }
}

/// A short sleeve on a coarse rigid cylinder (the shape of examples/sleeve_rigid_cylinder.json).
nlohmann::json sleeve_scene() {
  return nlohmann::json::parse(R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                           "hoop_scale": 0.9, "axial_scale": 0.95, "edge_length": 0.016,
                           "jitter": 0.3, "pin_first_ring": true, "pin_last_ring": true}},
    "body_material": {"rigid": true}
  })");
}

/// A coarse two-panel layout (examples/sleeve_two_panels.json on a rigid body).
nlohmann::json layout_scene() {
  return nlohmann::json::parse(R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.2, "edge_length": 0.015},
    "garment": {
      "layout": {
        "region": [{"name": "lower", "point": [0, 0, -0.05], "normal": [0, 0, 1]},
                   {"name": "upper", "point": [0, 0, 0.05], "normal": [0, 0, -1]}],
        "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0]}],
        "panels": [{"name": "front", "sides": ["+side"]},
                   {"name": "back", "sides": ["-side"]}],
        "pinned": [{"name": "lower cuff", "on_plane": "lower"},
                   {"name": "upper cuff", "on_plane": "upper"}]
      },
      "pattern": {"edge_length": 0.015, "scale": [0.95, 0.9], "grain": [0, 0, 1]}
    },
    "seam": {"youngs_modulus": 2e7},
    "body_material": {"rigid": true}
  })");
}

/// Files whose bytes must not change when regenerated from the state.
const char* const kSameBytes[] = {"garment.ply", "garment.csv", "body.ply",   "pieces.json",
                                  "pattern.svg", "pattern.dxf", "scene.json", "state.json"};

class ExportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tightfit_export_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write_scene(const std::string& name, const nlohmann::json& scene) {
    std::ofstream(dir_ / name) << scene.dump(2);
    return dir_ / name;
  }
  /// Runs `command SCENE --out DIR/run`, returns DIR/run.
  fs::path run(const std::string& command, const nlohmann::json& scene) {
    const fs::path out = dir_ / "run";
    const CliRun r = run_cli(command + " " + write_scene("scene.json", scene).string() + " --out " +
                             out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "state.json")) << r.output;
    return out;
  }
  /// The export's printed force residual and tolerance (N).
  static std::pair<double, double> residual(const std::string& output) {
    std::smatch m;
    const std::regex re(
        "force residual of the saved state ([0-9.e+-]+) N \\(tolerance ([0-9.e+-]+) N\\)");
    if (!std::regex_search(output, m, re)) return {-1.0, -1.0};
    return {std::stod(m[1]), std::stod(m[2])};
  }
  fs::path dir_;
};

TEST_F(ExportCli, SimulateRunIsRegeneratedExactly) {
  const fs::path original = run("simulate", sleeve_scene());
  const fs::path copy = dir_ / "copy";
  const CliRun r = run_cli("export " + original.string() + " --out " + copy.string());
  std::printf("%s", r.output.c_str());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : kSameBytes) EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  for (const char* f :
       {"report.html", "fit.glb", "pattern_a4.pdf", "pattern_letter.pdf", "pattern_full.pdf"})
    EXPECT_TRUE(fs::exists(copy / f)) << f;
  EXPECT_FALSE(fs::exists(copy / "history.json"));
  expect_json_near(read_json(copy / "result.json"), read_json(original / "result.json"), 1e-12);
  EXPECT_EQ(report_data(copy / "report.html"), report_data(original / "report.html"));
  // The ease table: the cylinder has no skeleton, so levels by planes along its axis (z)
  // every 5 cm across the sleeve (z in [-0.04, 0.04]): z = 0. The sleeve's pattern is
  // 0.9 times the cylinder's circumference around: an ease of about -10 %.
  const nlohmann::json measurements = read_json(original / "result.json").at("measurements");
  ASSERT_EQ(measurements.size(), 1u) << measurements.dump(2);
  const nlohmann::json& level = measurements[0];
  EXPECT_EQ(level.at("name"), "z 0.00 m");
  EXPECT_EQ(level.at("origin"), "planes");
  EXPECT_EQ(level.at("status"), "measured");
  EXPECT_NEAR(level.at("body_circumference_m").get<double>(), 2 * std::numbers::pi * 0.05,
              0.01 * 2 * std::numbers::pi * 0.05);
  EXPECT_NEAR(level.at("pattern_circumference_m").get<double>(), 0.9 * 2 * std::numbers::pi * 0.05,
              0.01 * 2 * std::numbers::pi * 0.05);
  EXPECT_NEAR(level.at("ease_percent").get<double>(), -10.0, 1.0);
  EXPECT_NEAR(level.at("fitted_stretch").get<double>(),
              level.at("garment_circumference_m").get<double>() /
                  level.at("pattern_circumference_m").get<double>(),
              1e-12);
  EXPECT_EQ(report_data(original / "report.html").at("measurements"), measurements);
  // fit.glb is y up: the cylinder's axis (z) was turned onto +y, so the body's length
  // (0.16 m side and two 0.05 m round caps) is its y extent, its 0.1 m diameter the
  // z extent; the export writes it alike.
  for (const fs::path& folder : {original, copy}) {
    const nlohmann::json gltf = glb_json(folder / "fit.glb");
    EXPECT_EQ(gltf["asset"]["extras"]["scene_up"], nlohmann::json({0.0, 0.0, 1.0}));
    const auto& body =
        gltf["accessors"]
            [gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<std::size_t>()];
    const double height = body["max"][1].get<double>() - body["min"][1].get<double>();
    EXPECT_NEAR(height, 0.16 + 2 * 0.05, 0.01);  // side and round caps
    EXPECT_LT(body["max"][2].get<double>() - body["min"][2].get<double>(), 0.11);
  }
  // The saved state is still the equilibrium Newton found.
  const auto [res, tol] = residual(r.output);
  const nlohmann::json newton = read_json(original / "result.json")["newton"];
  EXPECT_GE(res, 0.0) << r.output;
  EXPECT_LE(res, tol);
  // Printed with 4 digits: the residual Newton reported at the end of the run.
  EXPECT_NEAR(tol, newton["force_tolerance_n"].get<double>(), 1e-3 * tol);
  EXPECT_NEAR(res, newton["final_force_residual_n"].get<double>(), 1e-3 * res);
  // The solve's steps: chord steps reuse a factorization (those taken back have step 0),
  // the others made one (or more, with shifted retries).
  int chords = 0, taken_chords = 0;
  for (const auto& step : newton["history"]) {
    chords += step["chord"].get<bool>() ? 1 : 0;
    taken_chords += step["chord"].get<bool>() && step["step"].get<double>() > 0.0 ? 1 : 0;
  }
  EXPECT_EQ(newton["chord_steps"].get<int>(), taken_chords);
  EXPECT_EQ(newton["iterations"].get<int>(), static_cast<int>(newton["history"].size()));
  EXPECT_GE(newton["factorizations"].get<int>(), newton["iterations"].get<int>() - chords);
}

TEST_F(ExportCli, OptimizeRunKeepsHistoryAndCheckpointInPlace) {
  nlohmann::json scene = sleeve_scene();
  scene["optimize"] = {{"objectives", {{"stretch", {{"weight", 1}, {"min", 1.02}, {"max", 1.06}}}}},
                       {"regularizers", {{"seam_length", 1}}},
                       {"max_iterations", 3}};
  const fs::path original = run("optimize", scene);
  const fs::path copy = dir_ / "copy";
  fs::copy(original, copy, fs::copy_options::recursive);
  fs::remove(copy / "report.html");
  fs::remove(copy / "garment.ply");
  std::ofstream(copy / "notes.txt") << "mine\n";
  // In place: the outputs come back, other files (checkpoint, notes) are kept.
  const CliRun r = run_cli("export " + copy.string());
  std::printf("%s", r.output.c_str());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : kSameBytes) EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  for (const char* f : {"history.json", "checkpoint.json"})
    EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  EXPECT_EQ(read_text(copy / "notes.txt"), "mine\n");
  expect_json_near(read_json(copy / "result.json"), read_json(original / "result.json"), 1e-12);
  const nlohmann::json data = report_data(copy / "report.html");
  ASSERT_FALSE(data.is_null());
  EXPECT_EQ(data["history"].size(), 4u);  // iterations 0..3
  EXPECT_EQ(data, report_data(original / "report.html"));
  const auto [res, tol] = residual(r.output);
  EXPECT_GE(res, 0.0) << r.output;
  EXPECT_LE(res, tol);
}

TEST_F(ExportCli, RemeshedOptimizeRunIsRegeneratedExactly) {
  // A regular sleeve pushed to an across-the-grain stretch of 1.6-1.7 flattens its
  // triangles and is remeshed (measured: after iterations 1 and 3).
  nlohmann::json scene = sleeve_scene();
  scene["garment"]["sleeve"]["jitter"] = 0.0;
  scene["optimize"] = {
      {"objectives",
       {{"directional_stretch",
         {{"weight", 1}, {"min", 1.6}, {"max", 1.7}, {"direction", "across_grain"}}}}},
      {"remesh", {{"min_angle_deg", 40}}},
      {"max_iterations", 5}};
  const fs::path original = run("optimize", scene);
  const nlohmann::json state = read_json(original / "state.json");
  ASSERT_TRUE(state["pattern"].value("remeshed", false)) << "the run did not remesh";
  const fs::path copy = dir_ / "copy";
  const CliRun r = run_cli("export " + original.string() + " --out " + copy.string());
  std::printf("%s", r.output.c_str());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : kSameBytes) EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  EXPECT_EQ(read_text(copy / "history.json"), read_text(original / "history.json"));
  expect_json_near(read_json(copy / "result.json"), read_json(original / "result.json"), 1e-12);
  EXPECT_EQ(report_data(copy / "report.html"), report_data(original / "report.html"));
  const auto [res, tol] = residual(r.output);
  EXPECT_GE(res, 0.0) << r.output;
  EXPECT_LE(res, tol);

  // A saved pattern that does not fit the scene, or does not weld, is an input error
  // naming the file and the JSON path; nothing is written.
  auto expect_rejected = [&](const nlohmann::json& j, const std::string& message) {
    std::ofstream(original / "state.json") << j.dump();
    const CliRun bad = run_cli("export " + original.string() + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("state.json: " + message), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  };
  nlohmann::json j = state;
  j["pattern"]["pieces"][0]["name"] = "other";
  expect_rejected(j, "/pattern/pieces/0/name");
  j = state;
  j["pattern"]["seams"][0]["a"]["vertices"].erase(0);
  expect_rejected(j, "/pattern/seams/0");
  j = state;
  j["pattern"]["pinned"].erase(0);
  expect_rejected(j, "/pattern/pinned");
  j = state;
  j["pattern"]["pieces"][0]["triangles"][0][1] = 100000;
  expect_rejected(j, "/pattern/pieces/0/triangles/0/1");
  j = state;
  j["garment"].erase(0);
  expect_rejected(j, "/garment: ");
}

TEST_F(ExportCli, LayoutRunIsRegeneratedExactly) {
  const fs::path original = run("layout", layout_scene());
  const fs::path copy = dir_ / "copy";
  const CliRun r = run_cli("export " + original.string() + " --out " + copy.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"garment_embedded.ply", "layout.json", "pieces.json", "pattern.svg",
                        "pattern.dxf", "state.json"})
    EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  EXPECT_EQ(read_json(copy / "pieces.json")["pieces"].size(), 2u);
  EXPECT_FALSE(fs::exists(copy / "report.html"));
  EXPECT_EQ(r.output.find("force residual"), std::string::npos) << r.output;
}

TEST_F(ExportCli, SimulatedLayoutOnSoftBodyIsRegeneratedExactly) {
  nlohmann::json scene = layout_scene();
  scene.erase("body_material");
  scene["body"]["core"] = {{"soft_tissue", 0.02}};
  const fs::path original = run("simulate", scene);
  // The body is deformed: its saved positions are not the rest positions.
  EXPECT_GT(read_json(original / "result.json")["energies_j"]["body"].get<double>(), 0.0);
  const fs::path copy = dir_ / "copy";
  const CliRun r = run_cli("export " + original.string() + " --out " + copy.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : kSameBytes) EXPECT_EQ(read_text(copy / f), read_text(original / f)) << f;
  expect_json_near(read_json(copy / "result.json"), read_json(original / "result.json"), 1e-12);
}

TEST_F(ExportCli, MissingOrCorruptStateIsAnInputErrorWithoutOutput) {
  const fs::path empty = dir_ / "empty";
  fs::create_directories(empty);
  CliRun r = run_cli("export " + empty.string() + " --out " + (dir_ / "a" / "b").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find((empty / "state.json").string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "a"));

  const fs::path original = run("layout", layout_scene());
  const std::string state = read_text(original / "state.json");
  const std::string before = read_text(original / "layout.json");
  auto expect_rejected = [&](const std::string& text, const std::string& message) {
    std::ofstream(original / "state.json", std::ios::binary) << text;
    const CliRun bad = run_cli("export " + original.string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find((original / "state.json").string()), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find(message), std::string::npos) << bad.output;
    // DIR is untouched, no staging folder is left.
    EXPECT_EQ(read_text(original / "layout.json"), before);
    EXPECT_EQ(read_text(original / "state.json"), text);
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
    EXPECT_EQ(entries, 3u);  // empty, scene.json and run
  };
  expect_rejected(state.substr(0, state.size() / 2), "");
  nlohmann::json j = nlohmann::json::parse(state);
  j["version"] = 99;
  expect_rejected(j.dump(), "/version");
  j = nlohmann::json::parse(state);
  j["garment"][3] = "x";
  expect_rejected(j.dump(), "/garment/3");
}

TEST_F(ExportCli, StateOfAnotherGarmentIsAnInputError) {
  const fs::path original = run("simulate", sleeve_scene());
  const nlohmann::json state = read_json(original / "state.json");
  auto expect_rejected = [&](const nlohmann::json& j, const std::string& message) {
    std::ofstream(original / "state.json") << j.dump();
    const CliRun r = run_cli("export " + original.string() + " --out " + (dir_ / "copy").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("state.json"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "copy"));
  };
  nlohmann::json j = state;
  j["garment"].erase(j["garment"].size() - 1);
  expect_rejected(j, "/garment: ");
  j = state;
  j["scene"]["garment"]["sleeve"]["edge_length"] = 0.012;  // a finer sleeve
  expect_rejected(j, "/pattern/pieces/0/rest");
  j = state;
  j["body"].erase(0);
  expect_rejected(j, "/body: ");
  j = state;
  j["garment"][0][0] = 100000;
  expect_rejected(j, "/garment/0/0");
  j = state;
  j["scene"]["fabric"] = {{"youngs_modulus", "soft"}};
  expect_rejected(j, "/scene: ");
}

}  // namespace tightfit::export_cli_test
