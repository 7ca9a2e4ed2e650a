#include "tightfit/report/html.hpp"
#include "tightfit/report/shape_outputs.hpp"
#include "tightfit/report/simulation_outputs.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>

#include "report/support/fit_test_tools.hpp"
#include "report/support/fit_test_view.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/report/data.hpp"
#include "tightfit/report/fabric_outputs.hpp"

namespace tightfit::report_html_test {

/// The JSON embedded in a rendered report.
nlohmann::json embedded_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"tightfit-data\">";
  const auto begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const auto start = begin + open.size();
  const auto end = html.find("</script>", start);
  return nlohmann::json::parse(html.substr(start, end - start));
}

TEST(ReportHtml, SelfContainedPage) {
  const FitView view = test::band_on_sphere(8, 2);
  ReportOptions options;
  options.title = "Band <test> & fit";
  const std::string html = render_report_html(view, options);
  EXPECT_NE(html.find("<title>Band &lt;test&gt; &amp; fit</title>"), std::string::npos);
  EXPECT_NE(html.find("<script type=\"importmap\">"), std::string::npos);
  EXPECT_EQ(html.find("<!-- tightfit:"), std::string::npos);
  EXPECT_EQ(html.find("{{TITLE}}"), std::string::npos);
  // Nothing is loaded from elsewhere: no src/href attributes at all.
  EXPECT_EQ(html.find(" src="), std::string::npos);
  EXPECT_EQ(html.find(" href="), std::string::npos);

  const auto data = embedded_data(html);
  EXPECT_EQ(data["title"], options.title);
  ASSERT_EQ(data["colorings"].size(), 4u);
  EXPECT_EQ(data["colorings"][2]["unit"], "mmHg");
  EXPECT_EQ(data["colorings"][3]["categories"].size(), 3u);
  EXPECT_EQ(data["colorings"][0]["lut"].size(), 768u);
  EXPECT_TRUE(data["missing_colorings"].empty());
  ASSERT_EQ(data["pieces"].size(), 2u);
  EXPECT_EQ(data["pieces"][1]["name"], "back");
  EXPECT_EQ(data["history"].size(), 12u);
  EXPECT_EQ(data["stats"]["pieces"].size(), 2u);
}

TEST(ReportHtml, MissingFieldsAreListed) {
  FitView view = test::band_on_sphere(4, 1);
  view.garment_fields.erase(view.garment_fields.begin());  // no stretch_max
  const auto data = report_data_json(view, standard_colorings(), "t", "x");
  EXPECT_EQ(data["colorings"].size(), 3u);
  ASSERT_EQ(data["missing_colorings"].size(), 1u);
  EXPECT_NE(data["missing_colorings"][0].get<std::string>().find("stretch_max"), std::string::npos);
}

TEST(ReportHtml, MissingThreeJsIsAnError) {
  const FitView view = test::band_on_sphere(4, 1);
  ReportOptions options;
  options.three_module = "/nonexistent/three.module.js";
  try {
    render_report_html(view, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/three.module.js"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("install-deps.sh"), std::string::npos);
  }
  options = ReportOptions{};
  options.viewer_dir = "/nonexistent";
  EXPECT_THROW(render_report_html(view, options), InputError);
}

TEST(ReportHtml, TemplateWithoutMarkerIsAnError) {
  test::TempDir dir("report_template");
  std::filesystem::copy_file(default_report_viewer_dir() / "viewer.js", dir / "viewer.js");
  std::ofstream(dir / "template.html") << "<html>{{TITLE}}<!-- tightfit:data --></html>";
  ReportOptions options;
  options.viewer_dir = dir.path();
  EXPECT_THROW(render_report_html(test::band_on_sphere(4, 1), options), InputError);
}

/// Writes `view` as report.html and checks it in headless chromium with
/// tests/report/report_browser_check.mjs; returns the checker's JSON summary.
nlohmann::json check_in_browser(const FitView& view, const std::string& tag) {
  test::TempDir dir(tag);
  ReportOptions options;
  options.colorings = fit_report_colorings(view);
  write_report_html(dir / "report.html", view, options);
  // Screenshots stay in TIGHTFIT_REPORT_SHOTS when set (to look at them), else in the temp dir.
  const char* keep = std::getenv("TIGHTFIT_REPORT_SHOTS");
  const std::filesystem::path shots = keep != nullptr ? std::filesystem::path(keep) : dir / "shots";
  if (keep != nullptr) {
    std::filesystem::create_directories(shots);
    std::filesystem::copy_file(dir / "report.html", shots / "report.html",
                               std::filesystem::copy_options::overwrite_existing);
  }
  const auto result = test::run_command(
      "node " + test::shell_quote(test::source_path("tests/report/report_browser_check.mjs")) +
          " " + test::shell_quote(dir / "report.html") + " " + test::shell_quote(shots),
      dir / "browser.log");
  EXPECT_EQ(result.exit_code, 0) << "report.html failed in headless chromium (needs node, "
                                 << "/usr/bin/chromium and report/node_modules; see "
                                 << "scripts/install-deps.sh):\n"
                                 << result.output;
  auto summary = nlohmann::json::parse(result.output, nullptr, false);
  if (summary.is_discarded()) summary = {{"failures", {result.output}}};
  return summary;
}

TEST(ReportHtml, OpensInHeadlessChromiumSlow) {
  FitView view = test::band_on_sphere(32, 8);
  // Two pressure regions: the front piece's faces and every other face.
  FitRegion front{"front", 20 * kPascalPerMmHg, 30 * kPascalPerMmHg, {}};
  FitRegion alternate{"alternate", 0.0, 10 * kPascalPerMmHg, {}};
  for (int f = 0; f < view.garment.num_faces(); ++f) {
    if (f % 2 == 0) alternate.faces.push_back(f);
  }
  front.faces = resolved_piece_faces(view)[0];
  std::sort(front.faces.begin(), front.faces.end());
  view.pressure_regions = {front, alternate};
  // An optimization run: the pieces' outlines before it (shrunk by 5 %), a summary.
  for (const PatternPiece& piece : view.pattern.pieces) {
    Points2 outline(static_cast<Eigen::Index>(piece.boundary.size()), 2);
    for (size_t i = 0; i < piece.boundary.size(); ++i)
      outline.row(static_cast<Eigen::Index>(i)) = 0.95 * piece.rest.row(piece.boundary[i]);
    view.initial_outlines.push_back(outline);
  }
  view.summary = {{"command", "optimize"},    {"scene", "band.json"},
                  {"status", "converged"},    {"stop_reason", "gradient norm 1e-9 <= 1e-8"},
                  {"iterations", 11},         {"objective_initial", 2.0},
                  {"objective_final", 0.018}, {"seconds", 12.5},
                  {"version", "0.1.0"}};
  view.pinned_vertices = {0, 1, 2, 3};
  // One seam (front's right column to back's left column) and a pinned edge.
  {
    const int cols = 32, rows = 8;
    Seam seam{"side seam A", {0, {}}, {1, {}}};
    for (int j = 0; j <= rows; ++j) {
      seam.a.vertices.push_back(j * (cols + 1) + cols);
      seam.b.vertices.push_back(j * (cols + 1));
    }
    PinnedBoundary waistband{"waistband", 0, {}};
    for (int i = 0; i <= cols; ++i) waistband.vertices.push_back(rows * (cols + 1) + i);
    view.pattern.seams = {seam};
    view.pattern.pinned = {waistband};
    view.seams = pattern_seam_statistics(view.pattern);
    view.seams[0].has_fit = true;
    view.seams[0].sewn_length = 1.25 * view.seams[0].length_a;
    view.seams[0].traction_mean = 31.5;
    view.seams[0].traction_max = 47.2;
  }
  // A pose: the garment and the body turned by 40° about the x axis, some of it sliding.
  {
    const Mat3 R = Eigen::AngleAxisd(40.0 * EIGEN_PI / 180.0, Vec3::UnitX()).toRotationMatrix();
    FitPose pose;
    pose.name = "turned";
    pose.garment = view.garment.vertices * R.transpose();
    pose.garment_normals = view.garment_normals.rows() > 0
                               ? Points3(view.garment_normals * R.transpose())
                               : Points3(Points3::Zero(view.garment.vertices.rows(), 3));
    pose.body = view.body.vertices * R.transpose();
    pose.sliding_excess = VecX::LinSpaced(view.garment.num_faces(), 0.0, 2.0);
    pose.sliding_share = 0.25;
    view.poses = {pose};
  }
  // A shape objective: the target 10 % inside the garment, the initial garment 5 %
  // outside it, and the distance map.
  view.shape_target = TriMesh{0.9 * view.garment.vertices, view.garment.faces};
  view.initial_garment = TriMesh{1.05 * view.garment.vertices, view.garment.faces};
  {
    VecX distance(view.garment.vertices.rows());
    for (Eigen::Index i = 0; i < distance.size(); ++i)
      distance[i] = 0.1 * view.garment.vertices.row(i).norm();
    view.garment_fields.push_back(shape_distance_field(view.garment.faces, distance));
  }
  // The ease table: a measured level and one the garment goes only part of the way around.
  {
    LevelMeasurement calf;
    calf.level = {"calf.L", "skeleton", "lowerleg01.L at 0.45", Vec3(0.17, 0.4, 0.02),
                  Vec3::UnitY()};
    calf.reached = true;
    calf.body_circumference = 0.352;
    calf.pattern_circumference = 0.303;
    calf.garment_circumference = 0.349;
    calf.pieces = {{"front", 0.1515}, {"back", 0.1515}};
    LevelMeasurement knee;
    knee.level = {"knee.L", "skeleton", "lowerleg01.L at 0", Vec3(0.15, 0.5, 0.03), Vec3::UnitY()};
    knee.reached = true;
    knee.skipped = "the garment does not go all the way around here";
    view.measurements.levels = {calf, knee};
  }
  // A measured knit with an unloading branch across the grain: the fabric section plots
  // both directions' curves (course twice: loading and worn) and the working points of
  // the garment and the two regions.
  {
    ClothMaterial knit;
    knit.thickness = 5e-4;
    knit.measured = std::make_shared<MeasuredFabric>(MeasuredFabric{
        "power-net <78/22>", FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 40.0, 130.0, 420.0}),
        FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 25.0, 80.0, 260.0}), std::nullopt,
        FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 15.0, 60.0, 240.0}), 0.0, 30.0});
    std::vector<ClothElementFit> elements(static_cast<std::size_t>(view.garment.num_faces()));
    for (std::size_t f = 0; f < elements.size(); ++f) {
      elements[f].grain_stretch = Vec2(1.2 + 0.001 * static_cast<double>(f % 7), 1.05);
      elements[f].deformed_area = 1e-4;
    }
    view.fabric = fabric_json(knit, nlohmann::json::object(), elements, view.pressure_regions);
  }
  const auto summary = check_in_browser(view, "report_browser");
  ASSERT_TRUE(summary.at("failures").empty()) << summary.dump(2);
  EXPECT_EQ(summary.at("fabricCurves"), 3);
  EXPECT_EQ(summary.at("fabricPoints"), 6);
  EXPECT_EQ(summary.at("fabricRows"), 3);
  EXPECT_NE(summary.at("fabricText").get<std::string>().find("power-net <78/22>"),
            std::string::npos)
      << summary.dump(2);
  EXPECT_EQ(summary.at("poses"), (nlohmann::json{"neutral", "turned"}));
  EXPECT_TRUE(summary.at("poseSwitchVisible").get<bool>());
  EXPECT_NE(summary.at("poseHint")
                .get<std::string>()
                .find("25.0 % of the free garment vertices would slide"),
            std::string::npos)
      << summary.dump(2);
  EXPECT_GT(summary.at("pixels").at("notBackground").get<double>(), 0.05);
  EXPECT_GT(summary.at("pixels").at("changed").get<double>(), 0.02);
  EXPECT_EQ(summary.at("statsRows"), 3);  // two pieces and the whole garment
  EXPECT_NE(summary.at("statsText").get<std::string>().find("lift-off"), std::string::npos);
  EXPECT_EQ(summary.at("regionRows"), 2);
  const std::string regions = summary.at("regionsText").get<std::string>();
  EXPECT_NE(regions.find("front"), std::string::npos);
  EXPECT_NE(regions.find("RAL-GZ 387"), std::string::npos);
  EXPECT_GT(summary.at("histogramBars").get<int>(), 5);
  EXPECT_GT(summary.at("liftoffBars").get<int>(), 0);  // the back piece lifts off in a sector
  EXPECT_EQ(summary.at("targetLines"), 2);
  // The synthetic pressure reaches 2800 Pa = 21 mmHg: no warning.
  EXPECT_EQ(summary.at("pressureWarnings"), 0);
  // The before/after overlay: one dashed initial outline per piece.
  EXPECT_EQ(summary.at("initialOutlines"), 2);
  // The total and each term, on a log axis with decade labels.
  EXPECT_EQ(summary.at("historyCurves"),
            (nlohmann::json{"objective (total)", "boundary spacing", "stretch"}));
  const auto ticks = summary.at("historyTicks").get<std::vector<std::string>>();
  EXPECT_NE(std::find(ticks.begin(), ticks.end(), "0.01"), ticks.end()) << summary.dump(2);
  EXPECT_NE(std::find(ticks.begin(), ticks.end(), "1"), ticks.end()) << summary.dump(2);
  // The shape section: a front and a side view, each with some of all three layers.
  EXPECT_TRUE(summary.at("shapeSectionVisible").get<bool>());
  ASSERT_EQ(summary.at("silhouettes").size(), 2u) << summary.dump(2);
  for (const auto& view_pixels : summary.at("silhouettes")) {
    EXPECT_GT(view_pixels.at("filled").get<double>(), 0.05) << summary.dump(2);
    EXPECT_GT(view_pixels.at("colours").get<int>(), 2) << summary.dump(2);
  }
  const auto colorings = summary.at("colorings").get<std::vector<std::string>>();
  EXPECT_NE(std::find_if(colorings.begin(), colorings.end(),
                         [](const std::string& c) {
                           return c.find("Distance to the shape target") != std::string::npos;
                         }),
            colorings.end())
      << summary.dump(2);
  // The seam table: one row, its pieces, the sewing stretch and the traction.
  EXPECT_EQ(summary.at("seamRows"), 1);
  const std::string seams = summary.at("seamsText").get<std::string>();
  for (const char* word : {"side seam A", "1.25", "31.5", "47.2", "mismatch"})
    EXPECT_NE(seams.find(word), std::string::npos) << word << " missing in: " << seams;
  // The measurements table: body, pattern, ease (30.3 / 35.2 − 1 = −13.9 %), fitted and
  // its stretch (34.9 / 30.3); the skipped level's reason.
  EXPECT_EQ(summary.at("measurementRows"), 2);
  const std::string measurements = summary.at("measurementsText").get<std::string>();
  for (const char* word :
       {"calf.L", "lowerleg01.L at 0.45", "35.2", "30.3", "-13.9", "34.9", "1.152", "front 15.2",
        "back 15.2", "knee.L", "skipped: the garment does not go all the way around"})
    EXPECT_NE(measurements.find(word), std::string::npos)
        << word << " missing in: " << measurements;
  // Seam sides on both pieces, named; the pinned edge.
  EXPECT_EQ(summary.at("seamEdges"), 2);
  EXPECT_EQ(summary.at("pinnedEdges"), 1);
  EXPECT_EQ(summary.at("edgeLabels"), (nlohmann::json{"side seam A", "waistband", "side seam A"}))
      << summary.dump(2);
  // The 3D view draws seams between the pieces and the garment's free edges; a colouring
  // by piece names the pieces.
  EXPECT_GT(summary.at("edges").at("seam").get<int>(), 0) << summary.dump(2);
  EXPECT_GT(summary.at("edges").at("free").get<int>(), 0) << summary.dump(2);
  const std::string legend_piece = summary.value("legendPiece", "");
  for (const PatternPiece& piece : view.pattern.pieces)
    EXPECT_NE(legend_piece.find(piece.name), std::string::npos) << legend_piece;
  const std::string run = summary.at("summaryText").get<std::string>();
  for (const char* word : {"optimize", "converged", "gradient norm", "11", "0.1.0", "ratio 0.009"})
    EXPECT_NE(run.find(word), std::string::npos) << word << " missing in: " << run;
}

TEST(ReportHtml, OpensWithoutBodyHistoryParametersOrRegimeSlow) {
  FitView view = test::band_on_sphere(8, 2);
  view.body = TriMesh{};
  view.history = nlohmann::json::array();
  view.parameters = nlohmann::json::object();
  std::erase_if(view.garment_fields, [](const FaceField& f) { return f.name == "regime"; });
  // Five times the synthetic pressure: up to 105 mmHg, above the 40 mmHg warning.
  for (FaceField& f : view.garment_fields)
    if (f.name == "pressure_pa" || f.name == "pressure_mmhg") f.values *= 5.0;
  const auto summary = check_in_browser(view, "report_browser_sparse");
  ASSERT_TRUE(summary.at("failures").empty()) << summary.dump(2);
  EXPECT_FALSE(summary.at("poseSwitchVisible").get<bool>());  // a fit without poses
  EXPECT_EQ(summary.at("colorings").size(), 4u);              // stretch max/min, pressure, piece
  EXPECT_EQ(summary.at("pressureWarnings"), 1);
  EXPECT_EQ(summary.at("regionRows"), 0);
  EXPECT_EQ(summary.at("measurementRows"), 0);
  EXPECT_EQ(summary.at("seamRows"), 0);
  EXPECT_FALSE(summary.at("shapeSectionVisible").get<bool>());
  EXPECT_EQ(summary.at("initialOutlines"), 0);
  EXPECT_EQ(summary.at("historyCurves").size(), 0u);
}

}  // namespace tightfit::report_html_test
