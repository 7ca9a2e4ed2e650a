#include "tightfit/report/pressure_statistics.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tightfit/body/generators.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/report/simulation_outputs.hpp"
#include "tightfit/scene/optimization_setup.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::pressure_statistics_test {

TEST(CompressionClasses, RalGz387BoundariesAreInclusive) {
  EXPECT_EQ(ral_gz_387_class(17.99), "below I");
  EXPECT_EQ(ral_gz_387_class(18.0), "I");
  EXPECT_EQ(ral_gz_387_class(21.0), "I");
  EXPECT_EQ(ral_gz_387_class(22.0), "between I and II");
  EXPECT_EQ(ral_gz_387_class(23.0), "II");
  EXPECT_EQ(ral_gz_387_class(32.0), "II");
  EXPECT_EQ(ral_gz_387_class(33.0), "between II and III");
  EXPECT_EQ(ral_gz_387_class(34.0), "III");
  EXPECT_EQ(ral_gz_387_class(46.0), "III");
  EXPECT_EQ(ral_gz_387_class(48.9), "between III and IV");
  EXPECT_EQ(ral_gz_387_class(49.0), "IV");
  EXPECT_TRUE(in_burn_scar_range(15.0) && in_burn_scar_range(25.0));
  EXPECT_FALSE(in_burn_scar_range(14.9) || in_burn_scar_range(25.1));
  EXPECT_TRUE(in_face_mask_range(20.0) && in_face_mask_range(32.0));
  EXPECT_FALSE(in_face_mask_range(19.9) || in_face_mask_range(32.1));
}

TEST(CompressionClasses, AreaWeightedMoments) {
  const VecX p = (VecX(3) << 100.0, 200.0, 1000.0).finished();
  const PressureMoments m = pressure_moments(p, {1.0, 3.0, 5.0}, {0, 1});
  EXPECT_DOUBLE_EQ(m.area, 4.0);
  EXPECT_DOUBLE_EQ(m.mean, 175.0);
  EXPECT_NEAR(m.std, std::sqrt((75.0 * 75.0 + 3 * 25.0 * 25.0) / 4.0), 1e-12);
}

TEST(CompressionClasses, HistogramHasNiceBinsAndAZeroEdge) {
  // 4 faces: -0.5, 3.3, 7.9 and 10 mmHg with areas 1, 2, 3, 4.
  VecX p(4);
  p << -0.5, 3.3, 7.9, 10.0;
  p *= kPascalPerMmHg;
  const PressureHistogram h = pressure_histogram(p, {1.0, 2.0, 3.0, 4.0}, {0, 1, 2, 3}, 10);
  ASSERT_GE(h.edges_mmhg.size(), 2u);
  ASSERT_EQ(h.area_m2.size() + 1, h.edges_mmhg.size());
  const double width = h.edges_mmhg[1] - h.edges_mmhg[0];
  EXPECT_NEAR(width, 2.0, 1e-12);  // range 10.5 / 10 bins -> 1.05 -> nice 2
  EXPECT_LE(h.edges_mmhg.front(), -0.5);
  EXPECT_GT(h.edges_mmhg.back(), 10.0);
  bool zero_edge = false;
  for (double e : h.edges_mmhg) zero_edge |= std::abs(e) < 1e-12;
  EXPECT_TRUE(zero_edge);
  double total = 0.0;
  for (double a : h.area_m2) total += a;
  EXPECT_DOUBLE_EQ(total, 10.0);
  EXPECT_DOUBLE_EQ(h.area_m2.front(), 1.0);  // the lift-off face alone in [-2, 0)
  EXPECT_DOUBLE_EQ(h.area_m2.back(), 4.0);   // 10 mmHg in [10, 12)
}

const char* kSphere = R"({"body": {"generator": "sphere", "radius": 0.1},
  "garment": {"cover": {"scale": 0.9}}})";

std::string parse_error(const nlohmann::json& doc) {
  try {
    parse_scene(doc, "bad.json", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PressureRegionScene, RegionsAndRelaxationAreRead) {
  nlohmann::json doc = nlohmann::json::parse(kSphere);
  doc["fabric"] = {{"youngs_modulus", 1e6}, {"relaxation", 0.35}};
  doc["pressure"] = {{"regions",
                      {{{"name", "top"},
                        {"above", {{"point", {0, 0.05, 0}}, {"normal", {0, 2, 0}}}},
                        {"transition", 0.005},
                        {"min_mmhg", 23},
                        {"max_mmhg", 32}},
                       {{"name", "all"}, {"min_pa", 100}, {"max_pa", 200}}}}};
  const SceneSpec s = parse_scene(doc, "scene.json", ".");
  EXPECT_DOUBLE_EQ(s.materials.fabric.youngs_modulus, 0.65e6);
  ASSERT_EQ(s.pressure_regions.size(), 2u);
  const PressureRegion& top = s.pressure_regions[0];
  EXPECT_EQ(top.name, "top");
  ASSERT_TRUE(top.above.has_value());
  EXPECT_FALSE(top.below.has_value());
  EXPECT_NEAR(top.above->normal.y(), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(top.transition, 0.005);
  EXPECT_NEAR(top.min_pa, 23 * kPascalPerMmHg, 1e-9);
  EXPECT_NEAR(top.max_pa, 32 * kPascalPerMmHg, 1e-9);
  EXPECT_DOUBLE_EQ(s.pressure_regions[1].transition, 0.01);  // default

  nlohmann::json bad = doc;
  bad["fabric"]["relaxation"] = 1.0;
  EXPECT_NE(parse_error(bad).find("/fabric/relaxation"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["pressure"]["regions"][1]["min_mmhg"] = 1;
  EXPECT_NE(parse_error(bad).find("/pressure/regions/1"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["pressure"]["regions"][0]["above"]["normal"] = {0, 0, 0};
  EXPECT_NE(parse_error(bad).find("/pressure/regions/0/above/normal"), std::string::npos)
      << parse_error(bad);
  bad = doc;
  bad["pressure"]["regions"][0]["pieces"] = nlohmann::json::array();
  EXPECT_NE(parse_error(bad).find("pieces"), std::string::npos) << parse_error(bad);
}

TEST(PressureRegionScene, BoneRegionsNeedTheRigWhichIsLoaded) {
  nlohmann::json doc = nlohmann::json::parse(kSphere);
  doc["pressure"] = {
      {"regions",
       {{{"name", "thigh"}, {"bones", {"upperleg01.L"}}, {"min_pa", 1}, {"max_pa", 2}}}}};
  EXPECT_NE(parse_error(doc).find("/pressure/regions/0/bones"), std::string::npos)
      << parse_error(doc);
  const std::string data = TIGHTFIT_DATA_DIR;
  doc["pressure"]["rig"] = {{"mesh", data + "/bodies/mh_male_regular.obj"},
                            {"weights", data + "/rig/default_weights.mhw"},
                            {"radius", 0.02}};
  const SceneSpec s = parse_scene(doc, "scene.json", ".");
  ASSERT_TRUE(s.pressure_rig);
  EXPECT_EQ(s.pressure_rig->vertices.rows(), 13380);
  EXPECT_DOUBLE_EQ(s.pressure_rig_radius, 0.02);
  EXPECT_EQ(s.pressure_regions[0].bones, std::vector<std::string>{"upperleg01.L"});
  doc["pressure"]["rig"]["weights"] = "missing.mhw";
  EXPECT_NE(parse_error(doc).find("missing.mhw"), std::string::npos) << parse_error(doc);
}

/// Writes `doc` as a scene file in a fresh folder and reads it as an optimization scene.
std::string optimization_error(const nlohmann::json& doc) {
  const auto dir = std::filesystem::temp_directory_path() / "tightfit_pressure_region_scene";
  std::filesystem::create_directories(dir);
  const auto file = dir / "scene.json";
  std::ofstream(file) << doc.dump();
  try {
    read_optimization_scene(file.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PressureRegionScene, TheObjectiveTakesItsTargetsFromOnePlace) {
  nlohmann::json doc = nlohmann::json::parse(kSphere);
  doc["optimize"] = {{"objectives", {{"pressure", {{"weight", 1}}}}}};
  EXPECT_NE(optimization_error(doc).find("/pressure/regions"), std::string::npos);
  doc["pressure"] = {{"regions", {{{"name", "all"}, {"min_pa", 100}, {"max_pa", 200}}}}};
  EXPECT_EQ(optimization_error(doc), "");
  doc["optimize"]["objectives"]["pressure"]["min_pa"] = 100;
  doc["optimize"]["objectives"]["pressure"]["max_pa"] = 200;
  EXPECT_NE(optimization_error(doc).find("not both"), std::string::npos);
}

struct RigidCover {
  Body body;
  std::unique_ptr<LimitSurface> surface;
  std::unique_ptr<GarmentSimulation> sim;
};

RigidCover rigid_cover() {
  RigidCover c;
  SphereParams sp;
  sp.radius = 0.1;
  sp.edge_length = 0.02;
  c.body.surface = sphere_surface(sp);
  c.body.volume.vertices = c.body.surface.vertices;
  c.body.volume.tets.resize(0, 4);
  c.surface = std::make_unique<LimitSurface>(c.body.surface);
  SimulationMaterials m;
  m.rigid_body = true;
  c.sim = std::make_unique<GarmentSimulation>(
      c.body, *c.surface, make_cover(*c.surface, c.body.surface.vertices, 0.9), m);
  c.sim->solve();
  return c;
}

TEST(PressureRegionStatistics, RegionsOfACoverOnARigidSphere) {
  const RigidCover c = rigid_cover();
  const FitAnalysis fit = c.sim->analyze();
  const double p0 = fit.pressure_mid_edge.mean();  // ~2T/R, nearly uniform
  PressureRegion all;
  all.name = "all";
  all.min_pa = 0.9 * p0;
  all.max_pa = 1.1 * p0;
  PressureRegion cap = all;
  cap.name = "cap";
  cap.above = RegionPlane{Vec3(0, 0.05, 0), Vec3::UnitY()};
  cap.min_pa = 2 * p0;  // nowhere inside
  cap.max_pa = 3 * p0;
  const nlohmann::json j =
      fit_statistics(*c.sim, fit, ShapeOperatorKind::kMidEdge,
                     resolve_fit_regions(*c.sim, PressureRegionSet{{all, cap}}, "scene.json"));
  ASSERT_EQ(j["pressure_regions"].size(), 2u);
  const nlohmann::json& ja = j["pressure_regions"][0];
  const nlohmann::json& jc = j["pressure_regions"][1];
  EXPECT_EQ(ja["faces"].get<int>(), fit.pressure_mid_edge.size());
  EXPECT_NEAR(ja["area_m2"].get<double>(), j["garment_area_m2"].get<double>(), 1e-12);
  EXPECT_DOUBLE_EQ(ja["share_in_target"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(jc["share_in_target"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(ja["lift_off_share"].get<double>(), 0.0);
  // A cap above y = R/2 holds (1 − 1/2)/2 = 1/4 of the sphere's area.
  EXPECT_NEAR(jc["area_m2"].get<double>() / ja["area_m2"].get<double>(), 0.25, 0.03);
  const double median = ja["pressure_mmhg"]["median"].get<double>();
  EXPECT_EQ(ja["ral_gz_387_class"].get<std::string>(), ral_gz_387_class(median));
  EXPECT_LT(ja["spread"].get<double>(), 0.01);  // uniform on the sphere
  EXPECT_LT(j["pressure_spread"].get<double>(), 0.01);
  double histogram_area = 0.0;
  for (const auto& a : ja["histogram"]["area_m2"]) histogram_area += a.get<double>();
  EXPECT_NEAR(histogram_area, ja["area_m2"].get<double>(), 1e-12);
  PressureRegion unknown = all;
  unknown.pieces = {"sleeve"};
  EXPECT_THROW(resolve_fit_regions(*c.sim, PressureRegionSet{{unknown}}, "scene.json"), InputError);
}

}  // namespace tightfit::pressure_statistics_test
