/// Layouts and initial patterns end to end: `simulate` converges on the
/// two-panel sleeve, the three-piece sphere cover and the four-piece pants with the
/// pieces scaled down 10 %. Each scene is an example in examples/, loaded and solved
/// exactly as `tightfit simulate` does (load_scene + make_simulation + solve).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "tightfit/scene/loader.hpp"

namespace tightfit::layout_scene_simulation_test {

const std::filesystem::path kExamples = std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "examples";

double triangle_area(const Points2& X, const Eigen::Index a, Eigen::Index b, Eigen::Index c) {
  const Vec2 u = X.row(b) - X.row(a), v = X.row(c) - X.row(a);
  return 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
}

/// Loads `scene` with every piece scaled down 10 % in both directions, solves, and
/// checks the equilibrium: converged below the force tolerance, most of the cloth taut
/// and pressing on the body.
void expect_converges_scaled_ten_percent(const std::string& scene_name, size_t pieces) {
  SceneSpec spec = read_scene(kExamples / scene_name);
  ASSERT_EQ(spec.garment.kind, GarmentKind::kLayout);
  spec.garment.pattern.scale = PieceScale{0.9, 0.9};
  spec.garment.pattern.piece_scale.clear();
  auto scene = load_scene(std::move(spec));
  ASSERT_TRUE(scene->build.has_value());
  ASSERT_EQ(scene->garment.pattern.pieces.size(), pieces);
  auto sim = make_simulation(*scene);
  const NewtonReport report = sim->solve();
  ASSERT_TRUE(report.converged) << report.message;
  EXPECT_LE(report.final_force_norm, report.tolerance);
  const FitAnalysis fit = sim->analyze();
  double taut_area = 0.0, area = 0.0, pressure = 0.0;
  const Garment& g = sim->garment();
  const Points2 rest = g.rest_positions();
  for (size_t e = 0; e < fit.elements.size(); ++e) {
    const auto t = g.topology->pattern_triangles.row(static_cast<Eigen::Index>(e));
    const double a = triangle_area(rest, t(0), t(1), t(2));
    area += a;
    if (fit.elements[e].regime == ClothRegime::kTaut) taut_area += a;
    pressure += a * fit.pressure_mid_edge[static_cast<Eigen::Index>(e)];
  }
  pressure /= area;
  std::printf(
      "%s: %d Newton iterations, residual %.2e N (tolerance %.2e N), taut %.1f %% of the "
      "area, mean pressure %.0f Pa, %d garment vertices, %d body tets\n",
      scene_name.c_str(), report.iterations, report.final_force_norm, report.tolerance,
      100 * taut_area / area, pressure, g.num_garment_vertices(), scene->body.volume.num_tets());
  EXPECT_GT(taut_area / area, 0.5);  // 10 % smaller pieces are stretched on the body
  EXPECT_GT(pressure, 0.0);
}

TEST(LayoutSceneSimulation, TwoPanelSleeveOnCylinderConverges) {
  expect_converges_scaled_ten_percent("sleeve_two_panels.json", 2);
}

TEST(LayoutSceneSimulationSlow, ThreePieceCoverOnSphereConverges) {
  expect_converges_scaled_ten_percent("cover_sphere_three_pieces.json", 3);
}

TEST(LayoutSceneSimulationSlow, FourPiecePantsOnTheLegsBodyConverge) {
  expect_converges_scaled_ten_percent("pants_legs.json", 4);
}

}  // namespace tightfit::layout_scene_simulation_test
