// The scene's "fabric": the isotropic and measured models, inline and in a file, the
// relaxation as unloading curves, the shear stiffness of a bias curve (checked against a
// simulated 45° strip of the law), and the errors of bad fabrics (file and JSON path).
#include "tightfit/scene/fabric_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::fabric_spec_test {

namespace fs = std::filesystem;
using nlohmann::json;

json measured() {
  return {{"model", "measured"},
          {"name", "power-net 78/22"},
          {"thickness", 0.0005},
          {"wale", {{"strain", {0, 0.2, 0.5, 1.0}}, {"tension_n_per_m", {0, 40, 130, 420}}}},
          {"course", {{"strain", {0, 0.2, 0.5, 1.0}}, {"tension_n_per_m", {0, 25, 80, 260}}}},
          {"coupling", 0.1},
          {"shear_n_per_m", 30}};
}

json scene_with(const json& fabric) {
  return {{"body", {{"generator", "cylinder"}, {"radius", 0.05}, {"length", 0.3}}},
          {"garment", {{"sleeve", {{"radius", 0.05}}}}},
          {"fabric", fabric}};
}

std::string error_of(const json& fabric, const fs::path& base = ".") {
  try {
    parse_scene(scene_with(fabric), "scene.json", base);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FabricSpec, AnInlineMeasuredFabricReachesTheMaterial) {
  const SceneSpec s = parse_scene(scene_with(measured()), "scene.json", ".");
  const ClothMaterial& m = s.materials.fabric;
  ASSERT_NE(m.measured, nullptr);
  EXPECT_EQ(m.measured->name, "power-net 78/22");
  EXPECT_DOUBLE_EQ(m.thickness, 0.0005);
  EXPECT_DOUBLE_EQ(m.measured->coupling, 0.1);
  EXPECT_DOUBLE_EQ(m.measured->shear_n_per_m, 30.0);
  EXPECT_NEAR(m.measured->wale.tension(0.5), 130.0, 1e-9);
  EXPECT_NEAR(m.measured->course.tension(1.0), 260.0, 1e-9);
  EXPECT_FALSE(m.measured->wale_unloading.has_value());
  EXPECT_TRUE(s.fabric_file.empty());
}

TEST(FabricSpec, TheIsotropicModelStaysTheDefault) {
  const SceneSpec s =
      parse_scene(scene_with({{"youngs_modulus", 2e6}, {"relaxation", 0.25}}), "scene.json", ".");
  EXPECT_EQ(s.materials.fabric.measured, nullptr);
  EXPECT_DOUBLE_EQ(s.materials.fabric.youngs_modulus, 1.5e6);
  const SceneSpec named = parse_scene(
      scene_with({{"model", "isotropic"}, {"name", "jersey"}, {"thickness", 2e-4}}), "s.json", ".");
  EXPECT_EQ(named.materials.fabric.measured, nullptr);
  EXPECT_DOUBLE_EQ(named.materials.fabric.thickness, 2e-4);
}

TEST(FabricSpec, RelaxationIsUnloadingCurvesScaledByOneMinusR) {
  json f = measured();
  f["relaxation"] = 0.2;
  const SceneSpec s = parse_scene(scene_with(f), "scene.json", ".");
  const MeasuredFabric& m = *s.materials.fabric.measured;
  ASSERT_TRUE(m.wale_unloading && m.course_unloading);
  for (double e : {0.05, 0.2, 0.37, 0.8, 1.3}) {
    EXPECT_NEAR(m.worn_wale().tension(e), 0.8 * m.wale.tension(e), 1e-9 * m.wale.tension(e));
    EXPECT_NEAR(m.worn_course().tension(e), 0.8 * m.course.tension(e), 1e-9 * m.course.tension(e));
  }
  f.erase("relaxation");
  f["unloading"] = {{"wale", {{"strain", {0.2, 1.0}}, {"tension_n_per_m", {20, 400}}}}};
  const SceneSpec u = parse_scene(scene_with(f), "scene.json", ".");
  const MeasuredFabric& mu = *u.materials.fabric.measured;
  EXPECT_NEAR(mu.worn_wale().tension(1.0), 400.0, 1e-9);
  EXPECT_FALSE(mu.course_unloading.has_value());
  EXPECT_NEAR(mu.worn_course().tension(1.0), 260.0, 1e-9);
}

TEST(FabricSpec, AFabricFileIsReadRelativeToTheSceneAndInlined) {
  const fs::path dir = fs::path(testing::TempDir()) / "fabric_spec_file";
  fs::create_directories(dir / "fabrics");
  std::ofstream(dir / "fabrics/knit.json") << measured().dump(2);
  const SceneSpec s =
      parse_scene(scene_with("fabrics/knit.json"), (dir / "scene.json").string(), dir);
  ASSERT_NE(s.materials.fabric.measured, nullptr);
  EXPECT_EQ(s.fabric_file, dir / "fabrics/knit.json");
  EXPECT_EQ(s.document["fabric"], measured());
  const std::string missing = error_of("fabrics/none.json", dir);
  EXPECT_NE(missing.find("scene.json: /fabric: no such fabric file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.json"), std::string::npos) << missing;
  json bad = measured();
  bad["coupling"] = 1.0;
  std::ofstream(dir / "fabrics/bad.json") << bad.dump(2);
  const std::string in_file = error_of("fabrics/bad.json", dir);
  EXPECT_NE(in_file.find("bad.json: /coupling: must lie in [0, 1)"), std::string::npos) << in_file;
}

/// The bias stiffness a 45° strip of `law` shows at small strain: the strip's Green strain
/// along n = (1, 1)/√2 is held at e, the lateral strain and the shear are free (found by
/// Newton on the law's energy), and the tension per unit width is t · n·S·n.
double simulated_bias_stiffness(const FabricLaw& law, double e) {
  const double r = std::numbers::sqrt2 / 2.0;
  Mat2 rot;
  rot << r, -r, r, r;  // columns n and t
  auto energy = [&](double a, double b) {
    Mat2 green;
    green << e, b, b, a;  // in the n–t frame
    const Mat2 c = Mat2::Identity() + 2.0 * rot * green * rot.transpose();
    return law.evaluate(strain_components(c), 0).value;
  };
  double a = -0.3 * e, b = 0.0;
  const double h = 1e-3 * e;
  for (int it = 0; it < 30; ++it) {
    const double ga = (energy(a + h, b) - energy(a - h, b)) / (2 * h);
    const double gb = (energy(a, b + h) - energy(a, b - h)) / (2 * h);
    const double haa = (energy(a + h, b) - 2 * energy(a, b) + energy(a - h, b)) / (h * h);
    const double hbb = (energy(a, b + h) - 2 * energy(a, b) + energy(a, b - h)) / (h * h);
    const double hab = (energy(a + h, b + h) - energy(a + h, b - h) - energy(a - h, b + h) +
                        energy(a - h, b - h)) /
                       (4 * h * h);
    const double det = haa * hbb - hab * hab;
    a -= (hbb * ga - hab * gb) / det;
    b -= (haa * gb - hab * ga) / det;
  }
  Mat2 green;
  green << e, b, b, a;
  const Mat2 c = Mat2::Identity() + 2.0 * rot * green * rot.transpose();
  const Mat2 s = law.second_piola(c);
  const Vec2 n(r, r);
  return law.material().thickness * n.dot(s * n) / e;
}

TEST(FabricSpec, ABiasCurveGivesTheShearThatMakesA45DegreeStripThatStiff) {
  json f = measured();
  f.erase("shear_n_per_m");
  f["regime_smoothing"] = 1e-9;
  f["wale"] = {{"strain", {0, 0.5}}, {"tension_n_per_m", {0, 100}}};   // 200 N/m, linear
  f["course"] = {{"strain", {0, 0.5}}, {"tension_n_per_m", {0, 60}}};  // 120 N/m, linear
  f["bias"] = {{"strain", {0, 0.5}}, {"tension_n_per_m", {0, 30}}};    // 60 N/m
  const SceneSpec s = parse_scene(scene_with(f), "scene.json", ".");
  const double shear = s.materials.fabric.measured->shear_n_per_m;
  EXPECT_GT(shear, 0.0);
  const FabricLaw law(s.materials.fabric);
  EXPECT_NEAR(simulated_bias_stiffness(law, 1e-5), 60.0, 60.0 * 1e-3);
  f["bias"] = {{"strain", {0, 0.5}},
               {"tension_n_per_m", {0, 200}}};  // stiffer than the series allows
  EXPECT_NE(error_of(f).find("/fabric/bias: the bias strip is at least as stiff"),
            std::string::npos)
      << error_of(f);
}

TEST(FabricSpec, BadFabricsAreErrorsNamingTheJsonPath) {
  auto expect = [](json f, const std::string& fragment) {
    const std::string e = error_of(f);
    EXPECT_NE(e.find(fragment), std::string::npos) << "got: " << e << "\nwanted: " << fragment;
  };
  json f = measured();
  f["wale"]["tension_n_per_m"] = {0, 40, 30, 420};
  expect(f, "scene.json: /fabric/wale: tension_n_per_m must be strictly increasing (point 2)");
  f = measured();
  f["course"]["strain"] = {0, -0.2, 0.5, 1.0};
  expect(f, "/fabric/course: strain must be finite and >= 0 (point 1)");
  f = measured();
  f["course"]["tension_n_per_m"] = {0, -25, 80, 260};
  expect(f, "/fabric/course: tension_n_per_m must be finite and >= 0 (point 1)");
  f = measured();
  f["wale"] = {{"strain", {0.2}}, {"tension_n_per_m", {40}}};
  f["wale"]["strain"] = json::array();
  f["wale"]["tension_n_per_m"] = json::array();
  expect(f, "/fabric/wale: a curve needs at least two points");
  f = measured();
  f["wale"]["strain"] = {0, 0.2, 0.5};
  expect(f, "/fabric/wale: strain has 3 points but tension_n_per_m has 4");
  f = measured();
  f["wale"]["strain"][1] = "x";
  expect(f, "/fabric/wale/strain/1: expected a number, got string");
  f = measured();
  f["coupling"] = 1.0;
  expect(f, "/fabric/coupling: must lie in [0, 1)");
  f = measured();
  f.erase("course");
  expect(f, "/fabric/course");
  f = measured();
  f.erase("shear_n_per_m");
  expect(f, "/fabric: needs exactly one of \"shear_n_per_m\"");
  f = measured();
  f["youngs_modulus"] = 1e6;
  expect(f, "/fabric/youngs_modulus: belongs to the isotropic model");
  f = measured();
  f["relaxation"] = 0.1;
  f["unloading"] = {{"wale", measured()["wale"]}};
  expect(f, "/fabric/unloading: give either unloading curves or a relaxation");
  f = measured();
  f["unloading"] = json::object();
  expect(f, "/fabric/unloading: needs a \"wale\" or a \"course\" curve");
  expect({{"wale", measured()["wale"]}}, "/fabric/wale: belongs to a measured fabric");
  expect({{"model", "woven"}}, "/fabric/model");
  expect(json(3), "/fabric: expected an object or the path of a fabric file, got number");
  expect(json(""), "/fabric: must name a fabric file");
}

TEST(FabricSpec, ShearFromBiasInvertsTheSeriesOfCompliances) {
  // 1/k45 = (kc + kw − 2κ) / (4 (kc kw − κ²)) + 1/(4G)
  const double kc = 120.0, kw = 200.0, c = 0.3, g = 25.0;
  const double kappa = c * std::sqrt(kc * kw);
  const double k45 = 1.0 / ((kc + kw - 2.0 * kappa) / (4.0 * (kc * kw - kappa * kappa)) + 0.25 / g);
  EXPECT_NEAR(shear_from_bias(kc, kw, c, k45), g, 1e-9 * g);
  EXPECT_LE(shear_from_bias(kc, kw, c, 2.0 * k45 * (1.0 + 4.0 * g)), 0.0);
}

}  // namespace tightfit::fabric_spec_test
