// The analytic check of a measured knit on a rigid cylinder: a sleeve of rest
// circumference 2πR/λ_h and rest length L/λ_a wrapped on a cylinder of radius R presses
// p = T(λ_h − 1) / (λ_a R), with T the strip curve of the direction that runs around
// the cylinder (course when the grain runs along the axis, wale when the grain is turned
// 90°): T is per unit *rest* width, and a rest width of 1 is λ_a wide on the body.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "physics_test_util.hpp"
#include "test_surfaces.hpp"
#include "tightfit/physics/cloth_analysis.hpp"
#include "tightfit/physics/fabric_law.hpp"

namespace tightfit::test::measured_sleeve_pressure_test {

/// A knit with a soft toe and a stiff rise in both directions, wale stiffer than course.
std::shared_ptr<const MeasuredFabric> soft_toe_knit() {
  auto m = std::make_shared<MeasuredFabric>(MeasuredFabric{
      "soft-toe knit",
      FabricCurve({0.0, 0.05, 0.1, 0.3, 0.6, 1.0}, {0.0, 3.0, 8.0, 60.0, 240.0, 560.0}),
      FabricCurve({0.0, 0.05, 0.1, 0.3, 0.6, 1.0}, {0.0, 1.5, 4.0, 25.0, 110.0, 300.0}),
      std::nullopt, std::nullopt, 0.0, 20.0});
  return m;
}

struct Sleeve {
  CylinderMesh mesh;
  std::shared_ptr<const Points2> rest;
  ClothEnergy cloth;
  VecX x;
};

/// The cylinder mesh (irregular: jittered nodes, random diagonals) with its pattern
/// unrolled and shrunk by (λ_h, λ_a); `grain_around` turns the pattern 90° so that the
/// grain (pattern y, the wale) runs around the cylinder instead of along it.
Sleeve make_sleeve(double R, double hoop, double axial, bool grain_around) {
  CylinderMesh m = cylinder_mesh(R, 0.1, 2 * M_PI, 96, 32, 0.2, true, 11);
  auto rest = std::make_shared<Points2>(m.param.rows(), 2);
  for (int p = 0; p < m.param.rows(); ++p) {
    const double u = R * m.param(p, 0) / hoop, v = m.param(p, 1) / axial;
    if (grain_around)
      rest->row(p) << -v, u;  // a rotation by 90°: orientation kept
    else
      rest->row(p) << u, v;
  }
  ClothMaterial material;
  material.thickness = 6e-4;
  material.measured = soft_toe_knit();
  ClothEnergy cloth(m.pattern_faces, *rest, m.to_garment, static_cast<int>(m.garment.rows()),
                    material);
  const VecX x = flatten(m.garment);
  return {std::move(m), std::move(rest), std::move(cloth), x};
}

/// The largest relative error of the mid-edge Young–Laplace pressure against
/// T(λ − 1)/(λ_a R). `per_element`: λ and λ_a are each element's own principal stretches
/// (a jittered element's chord spans a slightly different arc, which matters on a steep
/// soft toe); else the sleeve's, with the hoop stretch of the polygon (chords, not arcs).
double worst_pressure_error(double hoop, double axial, bool grain_around,
                            bool per_element = false) {
  const double R = 0.05;
  const Sleeve s = make_sleeve(R, hoop, axial, grain_around);
  const auto fit = analyze_cloth(s.cloth, s.x);
  const double chord = std::sin(M_PI / 96) / (M_PI / 96);
  const MeasuredFabric& knit = *s.cloth.material().measured;
  const FabricCurve& around = grain_around ? knit.wale : knit.course;
  const VecX p =
      young_laplace_pressure(fit, mid_edge_shape_operators(s.mesh.garment, s.mesh.garment_faces));
  double worst = 0.0;
  for (Eigen::Index e = 0; e < p.size(); ++e) {
    const double h = per_element ? fit[e].stretch[0] : hoop * chord;
    const double a = per_element ? fit[e].stretch[1] : axial;
    const double exact = around.tension(h - 1.0) / (a * R);
    worst = std::max(worst, std::abs(p[e] / exact - 1));
  }
  return worst;
}

TEST(MeasuredSleevePressure, CourseAroundTheCylinderOnTheStiffRise) {
  EXPECT_LT(worst_pressure_error(1.45, 1.05, false), 5e-3);
}

TEST(MeasuredSleevePressure, WaleAroundTheCylinderWhenTheGrainIsTurned) {
  EXPECT_LT(worst_pressure_error(1.45, 1.05, true), 5e-3);
}

TEST(MeasuredSleevePressure, OnTheSoftToe) {
  EXPECT_LT(worst_pressure_error(1.07, 1.02, false, true), 5e-3);
  EXPECT_LT(worst_pressure_error(1.07, 1.02, true, true), 5e-3);
}

TEST(MeasuredSleevePressure, TheGrainTurnedChangesThePressureByTheCurvesRatio) {
  const double R = 0.05, hoop = 1.3, axial = 1.0;
  const Sleeve course = make_sleeve(R, hoop, axial, false);
  const Sleeve wale = make_sleeve(R, hoop, axial, true);
  auto median_pressure = [](const Sleeve& s) {
    VecX p = young_laplace_pressure(analyze_cloth(s.cloth, s.x),
                                    mid_edge_shape_operators(s.mesh.garment, s.mesh.garment_faces));
    std::sort(p.begin(), p.end());
    return p[p.size() / 2];
  };
  const std::shared_ptr<const MeasuredFabric> knit = soft_toe_knit();
  const double chord = std::sin(M_PI / 96) / (M_PI / 96);
  const double ratio =
      knit->wale.tension(hoop * chord - 1) / knit->course.tension(hoop * chord - 1);
  EXPECT_NEAR(median_pressure(wale) / median_pressure(course), ratio, 5e-3 * ratio);
}

}  // namespace tightfit::test::measured_sleeve_pressure_test
