/// `tightfit simulate` with a measured knit named by file: the pressure on a rigid
/// cylinder against Laplace with the strip curve, result.json's fabric and working point,
/// the pattern labels, and a bad fabric refused with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "report/support/fit_test_tools.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/physics/fabric_curve.hpp"

namespace tightfit::measured_fabric_cli_test {

namespace fs = std::filesystem;

TEST(MeasuredFabricCli, ASleeveOnARigidCylinderPressesTheCurvesTensionOverItsRadius) {
  test::TempDir dir("measured_fabric_cli");
  const fs::path scene = test::source_path("examples/sleeve_measured_knit.json");
  const auto run =
      test::run_command(std::string(TIGHTFIT_CLI) + " simulate " + test::shell_quote(scene) +
                            " --out " + test::shell_quote(dir / "run"),
                        dir / "simulate.log");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json result = read_json_file((dir / "run/result.json").string());
  const nlohmann::json& fabric = result.at("fabric");
  EXPECT_EQ(fabric.at("model"), "measured");
  const nlohmann::json& garment = fabric.at("working_points").at(0);
  EXPECT_EQ(garment.at("region"), "garment");
  // The working point lies on the file's course curve.
  const nlohmann::json file =
      read_json_file(test::source_path("data/fabrics/warp_knit_powernet.json").string());
  const FabricCurve course(file["course"]["strain"].get<std::vector<double>>(),
                           file["course"]["tension_n_per_m"].get<std::vector<double>>());
  const double hoop_strain = garment["course"]["strain"].get<double>();
  const double axial_stretch = 1.0 + garment["wale"]["strain"].get<double>();
  EXPECT_NEAR(hoop_strain, 1.0 / 0.85 - 1.0, 0.01);  // the sleeve's hoop scale, less chords
  EXPECT_NEAR(axial_stretch, 1.0 / 0.95, 1e-3);
  const double tension = course.tension(hoop_strain);
  EXPECT_NEAR(garment["course"]["tension_n_per_m"].get<double>(), tension, 1e-9 * tension);
  // Laplace on a cylinder, T per unit rest width: p = T / (λ_a R).
  const double laplace = tension / (axial_stretch * 0.05);
  const double median = result["fit"]["pressure_pa"]["median"].get<double>();
  EXPECT_NEAR(median, laplace, 5e-3 * laplace);
  // The sleeve's seam runs along the cylinder's axis, the body's up axis: 0°.
  EXPECT_LT(result["fit"]["seams"][0]["angle_to_up_deg"].get<double>(), 1.0);
  // The console ends with the fit in a pattern maker's terms and the report to open.
  EXPECT_NE(run.output.find("fabric stretched "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("open " + (dir / "run/report.html").string()), std::string::npos)
      << run.output;
  // The labels name the fabric and the worn stretch per direction.
  std::ifstream svg(dir / "run/pattern.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("fabric power-net"), std::string::npos);
  EXPECT_NE(text.find("worn stretch course 1.17 to 1.17, wale 1.05 to 1.05"), std::string::npos);
  EXPECT_EQ(text.find("fabric E "), std::string::npos);
}

/// A two-panel layout sleeve on a rigid cylinder (axis z) of the library's power-net, with
/// the pieces' grain along `grain`; returns {median pressure (Pa), Laplace's pressure with
/// the curve of the direction around the cylinder at the fit's working point}.
std::pair<double, double> layout_sleeve_pressure(const std::string& grain, bool wale_around,
                                                 const fs::path& dir) {
  const std::string scale = wale_around ? "[0.85, 0.95]" : "[0.95, 0.85]";
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.3, "edge_length": 0.006},
    "garment": {"layout": {
        "region": [{"name": "low", "point": [0, 0, -0.06], "normal": [0, 0, 1]},
                   {"name": "high", "point": [0, 0, 0.06], "normal": [0, 0, -1]}],
        "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0]}],
        "panels": [{"name": "right", "sides": ["+side"]}, {"name": "left", "sides": ["-side"]}],
        "pinned": [{"name": "low cuff", "on_plane": "low"},
                   {"name": "high cuff", "on_plane": "high"}]},
      "pattern": {"edge_length": 0.008, "scale": )"
                                    << scale << R"(, "grain": )" << grain << R"(}},
    "fabric": ")" << test::source_path("data/fabrics/warp_knit_powernet.json").string()
                                    << R"(", "body_material": {"rigid": true}})";
  const auto run = test::run_command(std::string(TIGHTFIT_CLI) + " simulate " +
                                         test::shell_quote(dir / "scene.json") + " --out " +
                                         test::shell_quote(dir / "run"),
                                     dir / "simulate.log");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json result = read_json_file((dir / "run/result.json").string());
  const nlohmann::json& point = result["fabric"]["working_points"][0];
  const nlohmann::json& around = point[wale_around ? "wale" : "course"];
  const nlohmann::json& along = point[wale_around ? "course" : "wale"];
  const double laplace =
      around["tension_n_per_m"].get<double>() / ((1.0 + along["strain"].get<double>()) * 0.05);
  return {result["fit"]["pressure_pa"]["median"].get<double>(), laplace};
}

TEST(MeasuredFabricCli, TheGrainOfALayoutPieceTurnsTheKnitOnTheCylinder) {
  // Grain across the panels (around the cylinder): the wale presses; along the axis: the
  // course, at about half the pressure for the same stretch (this knit's wale is twice
  // as stiff).
  test::TempDir dir("measured_fabric_grain");
  fs::create_directories(dir / "around");
  fs::create_directories(dir / "along");
  const auto [wale_p, wale_laplace] = layout_sleeve_pressure("[0, 1, 0]", true, dir / "around");
  const auto [course_p, course_laplace] = layout_sleeve_pressure("[0, 0, 1]", false, dir / "along");
  EXPECT_NEAR(wale_p, wale_laplace, 5e-3 * wale_laplace);
  EXPECT_NEAR(course_p, course_laplace, 5e-3 * course_laplace);
  EXPECT_NEAR(wale_p / course_p, 2.0, 0.1);
}

TEST(MeasuredFabricCli, APressureDesignReachesTheTutorialsTargetBandsSlow) {
  // The tutorial's graduated calf sleeve in a measured power-net: at the start the lower
  // calf presses below its 20–25 mmHg band; the optimized pattern puts both regions'
  // medians in their bands.
  test::TempDir dir("measured_fabric_optimize");
  const auto run = test::run_command(
      std::string(TIGHTFIT_CLI) + " optimize " +
          test::shell_quote(test::source_path("examples/optimize_calf_sleeve_measured.json")) +
          " --out " + test::shell_quote(dir / "run"),
      dir / "optimize.log");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json result = read_json_file((dir / "run/result.json").string());
  int regions = 0;
  for (const nlohmann::json& r : result["fit"]["pressure_regions"]) {
    const double median = r["pressure_mmhg"]["median"].get<double>();
    EXPECT_GE(median, r["target_mmhg"]["min"].get<double>()) << r["name"];
    EXPECT_LE(median, r["target_mmhg"]["max"].get<double>()) << r["name"];
    ++regions;
  }
  EXPECT_EQ(regions, 2);
  EXPECT_EQ(result["fabric"]["working_points"].size(), 3u);
  // The console names each region's median against its target, then the stop rule last.
  EXPECT_NE(run.output.find("lower calf: median "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("(target 20 to 25 mmHg)"), std::string::npos) << run.output;
  EXPECT_LT(run.output.find("open "), run.output.rfind("stopped ("));
}

TEST(MeasuredFabricCli, ABadFabricIsExitTwoNamingTheFileAndPathWithNothingWritten) {
  test::TempDir dir("measured_fabric_bad");
  std::ofstream(dir / "knit.json") << R"({"model": "measured", "name": "bad",
    "wale": {"strain": [0, 0.2, 0.5], "tension_n_per_m": [0, 40, 30]},
    "course": {"strain": [0, 0.2, 0.5], "tension_n_per_m": [0, 20, 60]},
    "shear_n_per_m": 20})";
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                           "edge_length": 0.016, "pin_first_ring": true}},
    "fabric": "knit.json", "body_material": {"rigid": true}})";
  const auto run = test::run_command(std::string(TIGHTFIT_CLI) + " simulate " +
                                         test::shell_quote(dir / "scene.json") + " --out " +
                                         test::shell_quote(dir / "run"),
                                     dir / "simulate.log");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("knit.json: /wale: tension_n_per_m must be strictly increasing"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(dir / "run"));
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16},
    "garment": {"sleeve": {"radius": 0.05}}, "fabric": "missing.json"})";
  const auto missing = test::run_command(std::string(TIGHTFIT_CLI) + " simulate " +
                                             test::shell_quote(dir / "scene.json") + " --out " +
                                             test::shell_quote(dir / "run"),
                                         dir / "simulate2.log");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("scene.json: /fabric: no such fabric file"), std::string::npos)
      << missing.output;
  EXPECT_FALSE(fs::exists(dir / "run"));
}

TEST(FabricFitCli, StripTestsBecomeAFabricFileThatASceneSimulates) {
  test::TempDir dir("fabric_fit_cli");
  const std::string csv =
      test::shell_quote(test::source_path("tests/scene/data/strip_tests/knit_cycles.csv"));
  const std::string fit = std::string(TIGHTFIT_CLI) + " fabric fit " + csv +
                          " --width 50 --gauge 100 --thickness 0.6 --out " +
                          test::shell_quote(dir / "knit.json");
  const auto run = test::run_command(fit, dir / "fit.log");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(fs::is_regular_file(dir / "knit.svg"));
  const nlohmann::json fabric = read_json_file((dir / "knit.json").string());
  EXPECT_EQ(fabric["name"], "knit");
  EXPECT_DOUBLE_EQ(fabric["thickness"].get<double>(), 6e-4);
  EXPECT_NE(fabric["source"].get<std::string>().find("knit_cycles.csv"), std::string::npos);
  // Again: the files exist and are not replaced without --force.
  const auto again = test::run_command(fit, dir / "fit2.log");
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("exists: not replaced"), std::string::npos) << again.output;
  EXPECT_EQ(test::run_command(fit + " --force", dir / "fit3.log").exit_code, 0);
  // A bad file: exit 2, nothing written.
  std::ofstream(dir / "bad.csv") << "direction,extension_mm,force_n\nwale,1,oops\n";
  const auto bad = test::run_command(
      std::string(TIGHTFIT_CLI) + " fabric fit " + test::shell_quote(dir / "bad.csv") +
          " --width 50 --gauge 100 --out " + test::shell_quote(dir / "bad_knit.json"),
      dir / "bad.log");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.csv: line 2"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "bad_knit.json"));
  EXPECT_FALSE(fs::exists(dir / "bad_knit.svg"));
  // The fitted fabric in a scene: a sleeve on a rigid cylinder.
  std::ofstream(dir / "scene.json") << R"({
    "body": {"generator": "cylinder", "radius": 0.05, "length": 0.16, "edge_length": 0.014},
    "garment": {"sleeve": {"radius": 0.05, "axial_begin": -0.04, "axial_end": 0.04,
                           "hoop_scale": 0.85, "edge_length": 0.016,
                           "pin_first_ring": true, "pin_last_ring": true}},
    "fabric": "knit.json", "body_material": {"rigid": true}})";
  const auto sim = test::run_command(std::string(TIGHTFIT_CLI) + " simulate " +
                                         test::shell_quote(dir / "scene.json") + " --out " +
                                         test::shell_quote(dir / "run"),
                                     dir / "simulate.log");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const nlohmann::json result = read_json_file((dir / "run/result.json").string());
  EXPECT_EQ(result["fabric"]["name"], "knit");
  EXPECT_GT(result["fit"]["pressure_pa"]["median"].get<double>(), 0.0);
}

}  // namespace tightfit::measured_fabric_cli_test
