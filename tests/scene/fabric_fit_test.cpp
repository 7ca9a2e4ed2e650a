// The fabric fit (scene/fabric_fit.hpp) on synthetic strip tests whose curves are known
// (tests/scene/data/strip_tests/make_strip_tests.py): the fitted curves follow them, the
// cycles are found with and without a cycle column, and bad files are errors naming the
// file and line.
#include "tightfit/scene/fabric_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/scene/fabric_spec.hpp"

namespace tightfit::fabric_fit_test {

namespace fs = std::filesystem;

const fs::path kData = fs::path(TIGHTFIT_SOURCE_DIR) / "tests/scene/data/strip_tests";

/// The synthetic knit's loading curves (N/m) and unloading (r = 0.06 of the top strain).
double loading(const std::string& d, double e) {
  const double a = d == "wale" ? 300.0 : (d == "course" ? 120.0 : 60.0);
  const double b = d == "wale" ? 400.0 : (d == "course" ? 150.0 : 80.0);
  return a * e + b * e * e * e;
}
double unloading(const std::string& d, double e) {
  const double top = d == "wale" ? 0.8 : 1.0;
  const double r = 0.06 * top;
  return e <= r ? 0.0 : loading(d, e) * std::pow((e - r) / (top - r), 0.6);
}

FabricFitOptions options() {
  FabricFitOptions o;
  o.width_mm = 50.0;
  o.gauge_mm = 100.0;
  o.name = "synthetic knit";
  o.shear_n_per_m = 30.0;
  return o;
}

/// The fabric the fit wrote, as a scene reads it.
std::shared_ptr<const MeasuredFabric> read_back(const FabricFit& fit) {
  return parse_fabric_spec(fit.fabric, "fit.json", "/fabric", ".").material.measured;
}

TEST(FabricFit, TheFittedCurvesFollowTheKnitsLastCycle) {
  const FabricFit fit = fit_fabric(read_strip_test_csv(kData / "knit_cycles.csv"), options());
  const auto knit = read_back(fit);
  ASSERT_NE(knit, nullptr);
  EXPECT_EQ(knit->name, "synthetic knit");
  ASSERT_EQ(fit.directions.size(), 3u);
  EXPECT_EQ(fit.directions[0].cycle, 3);
  EXPECT_EQ(fit.directions[0].cycles, 3);
  EXPECT_TRUE(fit.fabric.contains("bias"));
  EXPECT_FALSE(fit.fabric.contains("shear_n_per_m"));
  for (const auto& [name, curve, worn, top] :
       {std::tuple{"wale", &knit->wale, &knit->worn_wale(), 0.8},
        std::tuple{"course", &knit->course, &knit->worn_course(), 1.0}}) {
    for (double e : {0.25, 0.4, 0.55, 0.7}) {
      const double t = loading(name, e * top);
      EXPECT_NEAR(curve->tension(e * top), t, 0.02 * t) << name << " loading at " << e * top;
      const double u = unloading(name, e * top);
      EXPECT_NEAR(worn->tension(e * top), u, 0.03 * u + 0.5) << name << " unloading at " << e * top;
    }
  }
  EXPECT_TRUE(fit.warnings.empty());
}

TEST(FabricFit, CyclesAreFoundWithoutACycleColumnAndAnEarlierOneCanBeFitted) {
  FabricFitOptions o = options();
  const std::vector<StripSample> rows = read_strip_test_csv(kData / "knit_no_cycle_column.csv");
  const FabricFit last = fit_fabric(rows, o);
  EXPECT_EQ(last.directions[0].cycles, 3);
  EXPECT_EQ(last.directions[0].cycle, 3);
  EXPECT_DOUBLE_EQ(last.fabric["shear_n_per_m"].get<double>(), 30.0);
  o.cycle = 1;
  const FabricFit first = fit_fabric(rows, o);
  // The first cycle loads 8 % stiffer than the third.
  const double t1 = first.fabric["wale"]["tension_n_per_m"].back().get<double>();
  const double t3 = last.fabric["wale"]["tension_n_per_m"].back().get<double>();
  EXPECT_NEAR(t1 / t3, 1.08, 0.01);
  o.cycle = 4;
  EXPECT_THROW(fit_fabric(rows, o), InputError);
  o.cycle = 0;
  o.shear_n_per_m = 0.0;
  try {
    fit_fabric(rows, o);
    ADD_FAILURE() << "no shear stiffness accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--shear"), std::string::npos) << e.what();
  }
}

std::string error_reading(const std::string& text) {
  const fs::path file = fs::path(testing::TempDir()) / "strip_bad.csv";
  std::ofstream(file) << text;
  try {
    read_strip_test_csv(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FabricFit, BadFilesAreErrorsNamingTheFileAndLine) {
  EXPECT_NE(error_reading("direction,force_n\nwale,1\n").find("no column \"extension_mm\""),
            std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n\nwale,1,x\n")
                .find("strip_bad.csv: line 2: \"force_n\" is not a number"),
            std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n\nweft,1,2\n").find("line 2: direction"),
            std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n\nwale,-1,2\n").find("must be >= 0"),
            std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n\nwale,1\n").find("no value for"),
            std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n,cycle\nwale,1,2,0\n").find("cycle"),
            std::string::npos);
  EXPECT_NE(error_reading("").find("empty file"), std::string::npos);
  EXPECT_NE(error_reading("direction,extension_mm,force_n\n").find("no data rows"),
            std::string::npos);
  // Only one direction: the other is missing.
  const fs::path file = fs::path(testing::TempDir()) / "strip_wale.csv";
  std::ofstream(file) << "direction,extension_mm,force_n\nwale,0,0\nwale,10,1\nwale,20,3\n";
  EXPECT_THROW(fit_fabric(read_strip_test_csv(file), options()), InputError);
}

}  // namespace tightfit::fabric_fit_test
