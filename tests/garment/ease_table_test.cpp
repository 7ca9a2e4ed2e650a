// The ease table: body and pattern circumferences at measurement levels, analytic on a
// prism "cylinder" with a tube garment, and the standard levels on a MakeHuman body.
#include "tightfit/garment/ease_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "garment/garment_test_meshes.hpp"
#include "support/test_pieces.hpp"
#include "tightfit/body/skeleton.hpp"
#include "tightfit/garment/measurement_levels.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit {
namespace ease_test {

constexpr double kRadius = 0.05;                 // m, body and garment
constexpr int kBodySegments = 64;                // around the body prism
constexpr int kColumns = 24;                     // garment columns around, over both pieces
constexpr double kBottom = 0.105, kTop = 0.295;  // the garment's extent along y (m)

/// A tube garment of two pieces (front, back: grid pieces of kColumns / 2 columns and
/// `rows` rows, each `scale` × half the body circumference wide) sewn on both sides
/// (`closed`) or on one only, fitted onto the circle of radius kRadius around the y
/// axis; its positions in `fitted`.
Garment tube_garment(double scale, bool closed, Points3& fitted, int rows = 9) {
  const int nx = kColumns / 2 + 1;
  const double width = scale * test::kPi * kRadius;  // half the pattern circumference
  Pattern pattern;
  for (const char* name : {"front", "back"}) {
    PatternPiece piece = test::grid_piece(nx, rows, width, kTop - kBottom, 0.0, 1);
    piece.name = name;
    pattern.pieces.push_back(std::move(piece));
  }
  auto column = [&](int piece, int i) {
    SeamSide side{piece, {}};
    for (int j = 0; j < rows; ++j) side.vertices.push_back(j * nx + i);
    return side;
  };
  pattern.seams.push_back({"right", column(0, nx - 1), column(1, 0)});
  if (closed) pattern.seams.push_back({"left", column(1, nx - 1), column(0, 0)});
  Garment garment = weld_pattern(std::move(pattern));
  fitted.resize(garment.num_garment_vertices(), 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < nx; ++i) {
        const double angle = 2.0 * test::kPi * (k * (nx - 1) + i) / kColumns;
        const int g = garment.topology->pattern_to_garment[static_cast<size_t>(
            garment.topology->piece_offset[static_cast<size_t>(k)] + j * nx + i)];
        fitted.row(g) << kRadius * std::cos(angle), kBottom + (kTop - kBottom) * j / (rows - 1),
            -kRadius * std::sin(angle);
      }
  return garment;
}

MeasurementLevel level_at(double y, const std::string& name = "calf") {
  return {name, "scene", "point", Vec3(0.0, y, 0.0), Vec3::UnitY()};
}

/// The perimeter of a regular n-gon inscribed in a circle of radius r.
double polygon_perimeter(double r, int n) { return 2.0 * n * r * std::sin(test::kPi / n); }

}  // namespace ease_test

using namespace ease_test;

TEST(EaseTable, TubeOnACylinderHasTheEaseOfItsPatternScale) {
  const TriMesh body = test::closed_cylinder(kRadius, 0.4, kBodySegments, 9);
  const double circle = 2.0 * test::kPi * kRadius;
  for (const double scale : {0.8, 0.9, 1.0}) {
    SCOPED_TRACE(scale);
    Points3 fitted;
    const Garment garment = tube_garment(scale, true, fitted);
    const EaseTable table = measure_ease({level_at(0.2037)}, body, garment, fitted);
    ASSERT_EQ(table.levels.size(), 1u);
    const LevelMeasurement& m = table.levels[0];
    ASSERT_EQ(m.skipped, "");
    EXPECT_TRUE(m.reached);
    // The body's cut is the inscribed 64-gon: shorter than the circle by at most
    // 2πr π² / (6 n²) (sin x ≥ x − x³/6).
    const double bound = circle * test::kPi * test::kPi / (6.0 * kBodySegments * kBodySegments);
    EXPECT_LE(m.body_circumference, circle);
    EXPECT_GE(m.body_circumference, circle - bound);
    EXPECT_NEAR(m.body_circumference, polygon_perimeter(kRadius, kBodySegments), 1e-12);
    // The level cuts the pattern straight across both pieces: their whole width.
    EXPECT_NEAR(m.pattern_circumference, scale * circle, 1e-12);
    ASSERT_EQ(m.pieces.size(), 2u);
    EXPECT_EQ(m.pieces[0].piece, "front");
    EXPECT_EQ(m.pieces[1].piece, "back");
    EXPECT_NEAR(m.pieces[0].width, scale * circle / 2.0, 1e-12);
    EXPECT_NEAR(m.pieces[1].width, scale * circle / 2.0, 1e-12);
    // Ease (s − 1) × 100 % up to the body's discretization: the body's perimeter is
    // circle (1 − δ) with 0 ≤ δ ≤ bound / circle.
    const double delta = bound / circle;
    EXPECT_GE(m.ease_percent(), (scale - 1.0) * 100.0 - 1e-9);
    EXPECT_LE(m.ease_percent(), (scale / (1.0 - delta) - 1.0) * 100.0 + 1e-9);
    // The fitted tube is the inscribed 24-gon, stretched from the pattern's width.
    EXPECT_NEAR(m.garment_circumference, polygon_perimeter(kRadius, kColumns), 1e-12);
    EXPECT_NEAR(m.fitted_stretch(), polygon_perimeter(kRadius, kColumns) / (scale * circle), 1e-12);
  }
}

TEST(EaseTable, LevelsTheGarmentDoesNotGoAroundAreSkippedWithTheReason) {
  const TriMesh body = test::closed_cylinder(kRadius, 0.4, kBodySegments, 9);
  Points3 fitted;
  const Garment garment = tube_garment(0.9, true, fitted);
  MeasurementLevel beside = level_at(0.2037, "beside");
  beside.point = Vec3(1.0, 0.2037, 0.0);
  beside.normal = Vec3::UnitX();
  MeasurementLevel outside = level_at(0.2037, "outside");
  outside.point = Vec3(0.2, 0.2037, 0.0);  // in the plane, but beside the body's cross-section
  const EaseTable table = measure_ease(
      {level_at(0.35, "above"), beside, level_at(0.2037, "calf"), outside}, body, garment, fitted);
  ASSERT_EQ(table.levels.size(), 4u);
  EXPECT_EQ(table.levels[3].skipped,
            "the level's point is not inside the body's cross-section there");
  EXPECT_FALSE(table.levels[3].reached);
  EXPECT_EQ(table.levels[0].skipped, "the garment does not reach this level");
  EXPECT_FALSE(table.levels[0].reached);
  EXPECT_EQ(table.levels[1].skipped, "the plane misses the body");
  EXPECT_FALSE(table.levels[1].reached);
  EXPECT_EQ(table.levels[2].skipped, "");
  EXPECT_EQ(table.levels[0].pattern_circumference, 0.0);
  const EaseTable kept = drop_uncovered(table);
  ASSERT_EQ(kept.levels.size(), 1u);
  EXPECT_EQ(kept.levels[0].level.name, "calf");

  // Sewn on one side only, the tube is open: the level is reached but not measured.
  Points3 open_fitted;
  const Garment open = tube_garment(0.9, false, open_fitted);
  const EaseTable partial =
      drop_uncovered(measure_ease({level_at(0.2037)}, body, open, open_fitted));
  ASSERT_EQ(partial.levels.size(), 1u);
  EXPECT_TRUE(partial.levels[0].reached);
  EXPECT_NE(partial.levels[0].skipped.find("does not go all the way around"), std::string::npos);
  EXPECT_TRUE(partial.levels[0].pieces.empty());
  EXPECT_TRUE(ease_label_lines(partial).empty());
}

TEST(EaseTable, LabelLinesGivePerPieceTheBodyPieceWidthAndEase) {
  const TriMesh body = test::closed_cylinder(kRadius, 0.4, kBodySegments, 9);
  Points3 fitted;
  const Garment garment = tube_garment(0.9, true, fitted);
  const EaseTable table = measure_ease({level_at(0.2037, "calf"), level_at(0.2537, "below-knee")},
                                       body, garment, fitted);
  const auto lines = ease_label_lines(table);
  ASSERT_EQ(lines.size(), 2u);
  // Body 2πr = 31.42 cm (the 64-gon: 31.39 cm), each piece 0.9 πr = 14.14 cm, ease
  // 0.9 / (1 − 0.04 %) − 1 = −9.96 %.
  const std::vector<std::string> expected = {"calf 31.4 cm, piece 14.1 cm, ease -10 %",
                                             "below-knee 31.4 cm, piece 14.1 cm, ease -10 %"};
  EXPECT_EQ(lines.at("front"), expected);
  EXPECT_EQ(lines.at("back"), expected);
}

TEST(MeasurementLevels, PlanesAcrossTheGarmentEveryFiveCentimetres) {
  Points3 fitted;
  const Garment garment = tube_garment(0.9, true, fitted);
  const std::vector<MeasurementLevel> levels =
      plane_levels(TriMesh{fitted, garment.topology->garment_triangles}, Vec3::UnitY(), 0.05);
  ASSERT_EQ(levels.size(), 3u);  // y = 0.15, 0.20, 0.25 within [0.105, 0.295]
  const char* names[] = {"y 0.15 m", "y 0.20 m", "y 0.25 m"};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(levels[k].name, names[k]);
    EXPECT_EQ(levels[k].origin, "planes");
    EXPECT_NEAR(levels[k].point.y(), 0.15 + 0.05 * static_cast<double>(k), 1e-12);
    EXPECT_LT(std::hypot(levels[k].point.x(), levels[k].point.z()), 0.01);  // inside the tube
    EXPECT_EQ(levels[k].normal, Vec3::UnitY());
  }
  // Two tubes side by side: two levels per height, told apart by x.
  Points3 two = fitted;
  const Garment g2 = tube_garment(0.9, true, two);
  TriMesh both;
  both.vertices.resize(2 * two.rows(), 3);
  both.vertices << two, two.rowwise() + Eigen::RowVector3d(0.3, 0.0, 0.0);
  both.faces.resize(2 * g2.topology->garment_triangles.rows(), 3);
  both.faces << g2.topology->garment_triangles,
      g2.topology->garment_triangles.array() + static_cast<int>(two.rows());
  const auto pairs = plane_levels(both, Vec3::UnitY(), 0.05);
  ASSERT_EQ(pairs.size(), 6u);
  EXPECT_EQ(pairs[0].name, "y 0.15 m (x +0.00 m)");
  EXPECT_EQ(pairs[1].name, "y 0.15 m (x +0.30 m)");
}

TEST(MeasurementLevels, StandardLevelsOnTheMakeHumanBodyHaveHumanGirths) {
  const TriMesh body =
      read_tri_mesh(std::string(TIGHTFIT_DATA_DIR) + "/bodies/mh_male_regular.obj");
  const auto skeleton =
      read_skeleton(std::string(TIGHTFIT_DATA_DIR) + "/rig/mh_male_regular.joints.json");
  const std::vector<MeasurementLevel> levels = skeleton_levels(skeleton);
  std::map<std::string, double> girth;
  for (const MeasurementLevel& level : levels) {
    EXPECT_EQ(level.origin, "skeleton");
    const auto c = body_circumference(body, level);
    ASSERT_TRUE(c.has_value()) << level.name;
    girth[level.name] = *c;
  }
  // 4 torso levels, 6 per leg, 4 per arm.
  EXPECT_EQ(levels.size(), 24u);
  // The calf level lies 45 % down the left shin bone, normal along it.
  const BoneSegment& shin = skeleton.at("lowerleg01.L");
  const auto calf =
      std::find_if(levels.begin(), levels.end(), [](const auto& l) { return l.name == "calf.L"; });
  ASSERT_NE(calf, levels.end());
  EXPECT_LT((calf->point - (shin.head + 0.45 * (shin.tail - shin.head))).norm(), 1e-12);
  EXPECT_LT((calf->normal - (shin.tail - shin.head).normalized()).norm(), 1e-12);
  EXPECT_EQ(calf->anchor, "lowerleg01.L at 0.45");
  // Adult male girths (cm ranges of anthropometric surveys), the leg narrowing from the
  // thigh to the ankle, and the body's two sides alike.
  const std::map<std::string, std::pair<double, double>> range = {
      {"neck", {0.32, 0.46}},   {"chest", {0.85, 1.15}},   {"waist", {0.70, 1.10}},
      {"hip", {0.85, 1.15}},    {"thigh.L", {0.45, 0.68}}, {"knee.L", {0.32, 0.45}},
      {"calf.L", {0.32, 0.45}}, {"ankle.L", {0.19, 0.28}}, {"bicep.L", {0.24, 0.38}},
      {"wrist.L", {0.14, 0.20}}};
  for (const auto& [name, r] : range) {
    EXPECT_GE(girth.at(name), r.first) << name;
    EXPECT_LE(girth.at(name), r.second) << name;
  }
  EXPECT_GT(girth.at("thigh.L"), girth.at("mid-thigh.L"));
  EXPECT_GT(girth.at("mid-thigh.L"), girth.at("calf.L"));
  EXPECT_GT(girth.at("calf.L"), girth.at("ankle.L"));
  EXPECT_GT(girth.at("bicep.L"), girth.at("wrist.L"));
  for (const char* limb : {"thigh", "knee", "calf", "ankle", "bicep", "wrist"}) {
    const double left = girth.at(std::string(limb) + ".L"),
                 right = girth.at(std::string(limb) + ".R");
    EXPECT_NEAR(left, right, 0.02 * left) << limb;
  }
}

}  // namespace tightfit
