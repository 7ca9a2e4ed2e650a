#include "tightfit/report/seam_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "objectives/objective_test_garments.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "support/cli_run.hpp"
#include "support/test_pieces.hpp"
#include "tightfit/patterns/json.hpp"

namespace tightfit::seam_statistics_test {

Points3 seam_test_positions(const test::GarmentState& s) {
  return Eigen::Map<const Points3>(s.x.data(), s.garment.num_garment_vertices(), 3);
}

TEST(SeamStatistics, UniformSleeveByHand) {
  // The regular sleeve of the seam traction test: the seam runs along the axis with
  // axial stretch 1, and the hoop stretch s gives the traction t S_xx on every element.
  const int nx = 17, ny = 6;
  const double r = 0.05, w = 0.9 * 2.0 * std::numbers::pi * r, h = 0.1;
  const test::GarmentState s = test::sleeve(nx, ny, r, w, h, 0.0, 1);
  const ClothMaterial m;
  const std::vector<SeamStatistics> seams =
      fit_seam_statistics(s.garment, seam_test_positions(s), m);
  ASSERT_EQ(seams.size(), 1u);
  const SeamStatistics& seam = seams[0];
  const double stretch = 2.0 * r * std::sin(std::numbers::pi / (nx - 1)) / (w / (nx - 1));
  const double traction = m.thickness * m.youngs_modulus /
                          (1.0 - m.poisson_ratio * m.poisson_ratio) * 0.5 *
                          (stretch * stretch - 1.0);
  EXPECT_EQ(seam.name, "axial seam");
  EXPECT_TRUE(seam.has_fit);
  EXPECT_NEAR(seam.length_a, h, 1e-12);
  EXPECT_NEAR(seam.length_b, h, 1e-12);
  EXPECT_NEAR(seam.mismatch(), 0.0, 1e-12);
  EXPECT_NEAR(seam.sewn_length, h, 1e-12);
  EXPECT_NEAR(seam.stretch_a(), 1.0, 1e-12);
  EXPECT_NEAR(seam.traction_mean, traction, 1e-9 * traction);
  EXPECT_NEAR(seam.traction_max, traction, 1e-9 * traction);
  EXPECT_NEAR(seam.traction_total, 2.0 * h * traction, 1e-9 * traction);
  EXPECT_NEAR(seam.angle_to_up_deg, 90.0, 1e-9);  // the sleeve's axis is z: the seam lies across y
  // Against the body's up axis when it is the sleeve's (a generated cylinder along z): 0.
  EXPECT_NEAR(
      fit_seam_statistics(s.garment, seam_test_positions(s), m, Vec3::UnitZ())[0].angle_to_up_deg,
      0.0, 1e-9);

  // The sleeve turned so that its axis is y: the seam runs up, angle 0; sheared into a
  // helix of pitch angle 30° from the axis: 30°.
  Points3 x = seam_test_positions(s);
  Points3 turned(x.rows(), 3), helix(x.rows(), 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    turned.row(i) << x(i, 0), x(i, 2), x(i, 1);
    const double a = std::atan2(x(i, 1), x(i, 0)) + x(i, 2) * std::tan(std::numbers::pi / 6) / r;
    helix.row(i) << r * std::cos(a), x(i, 2), r * std::sin(a);
  }
  EXPECT_NEAR(fit_seam_statistics(s.garment, turned, m)[0].angle_to_up_deg, 0.0, 1e-9);
  EXPECT_NEAR(fit_seam_statistics(s.garment, helix, m)[0].angle_to_up_deg, 30.0, 0.5);
}

TEST(SeamStatistics, MismatchAndSewingStretchOfUnequalSides) {
  // Side b 2 % longer in the pattern than side a: a 2 mm mismatch on a 100 mm seam, and
  // side b is sewn compressed (stretch 1/1.02) while side a keeps its length.
  const double h = 0.1;
  test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, h, 0.0, 1);
  Pattern pattern = s.garment.pattern;
  for (int v : pattern.seams[0].b.vertices) pattern.pieces[0].rest(v, 1) *= 1.02;
  const std::vector<SeamStatistics> lengths = pattern_seam_statistics(pattern);
  ASSERT_EQ(lengths.size(), 1u);
  EXPECT_FALSE(lengths[0].has_fit);
  EXPECT_NEAR(lengths[0].length_b, 1.02 * h, 1e-12);
  EXPECT_NEAR(lengths[0].mismatch(), 0.02 * h, 1e-12);
  const nlohmann::json j = seam_statistics_json(lengths[0]);
  EXPECT_NEAR(j["mismatch_mm"].get<double>(), 2.0, 1e-9);
  EXPECT_FALSE(j.contains("sewn_length_mm"));

  s.garment.pattern = pattern;
  const SeamStatistics fit =
      fit_seam_statistics(s.garment, seam_test_positions(s), ClothMaterial{})[0];
  EXPECT_NEAR(fit.stretch_a(), 1.0, 1e-12);
  EXPECT_NEAR(fit.stretch_b(), 1.0 / 1.02, 1e-12);
  const nlohmann::json jf = seam_statistics_json(fit);
  EXPECT_NEAR(jf["sewn_length_mm"].get<double>(), 100.0, 1e-9);
  EXPECT_GT(jf["traction_max_n_per_m"].get<double>(), 0.0);
}

TEST(SeamStatistics, PiecesJsonCarriesSeamLengthsAndReadsBack) {
  const test::GarmentState s = test::sleeve(9, 5, 0.05, 0.28, 0.1, 0.0, 1);
  const std::vector<SeamStatistics> fit =
      fit_seam_statistics(s.garment, seam_test_positions(s), ClothMaterial{});
  const auto dir = test::scratch_dir("seam_statistics_pieces");
  const std::filesystem::path file = dir / "pieces.json";
  write_pieces_json(s.garment.pattern, PatternExportOptions{}, file, &fit);
  const nlohmann::json j = nlohmann::json::parse(test::read_text(file));
  const nlohmann::json& seam = j["seams"][0];
  EXPECT_NEAR(seam["length_a_mm"].get<double>(), 100.0, 1e-9);
  EXPECT_NEAR(seam["mismatch_mm"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(seam["fit"]["sewn_length_mm"].get<double>(), 100.0, 1e-9);
  EXPECT_NEAR(seam["fit"]["traction_mean_n_per_m"].get<double>(), fit[0].traction_mean, 1e-9);
  const Pattern back = read_pieces_json(file);
  ASSERT_EQ(back.seams.size(), 1u);
  EXPECT_EQ(back.seams[0].a.vertices, s.garment.pattern.seams[0].a.vertices);

  const std::vector<SeamStatistics> wrong;  // not one per seam
  EXPECT_THROW(write_pieces_json(s.garment.pattern, PatternExportOptions{}, dir / "x.json", &wrong),
               std::invalid_argument);
}

}  // namespace tightfit::seam_statistics_test
