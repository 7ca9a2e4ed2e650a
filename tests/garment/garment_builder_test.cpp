#include "tightfit/garment/garment_builder.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/pattern_svg.hpp"

namespace tightfit {
namespace {

LayoutSpec spec_from(const std::string& text, const std::string& source = "layout.json") {
  const auto j = nlohmann::json::parse(text);
  JsonFields f(j, source, "");
  return parse_layout_spec(f, "");
}

const char* kSleeve = R"({
  "region": [{"name": "bottom", "point": [0, 0.1, 0], "normal": [0, 1, 0]},
             {"name": "top", "point": [0, 0.4, 0], "normal": [0, -1, 0]}],
  "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0.1]}],
  "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
  "pinned": [{"name": "cuff", "on_plane": "bottom"}, {"name": "top", "nearest": [0.05, 0.41, 0]}]
})";

void print_report(const GarmentBuild& b) {
  for (const auto& p : b.pieces)
    std::printf("  piece %-12s area err %.2e  mean |J|-1 %.2e  max %.2e  angle mean %.3f max %.3f deg  "
                "%d verts %d tris, min angle %.1f\n",
                p.name.c_str(), p.distortion.area_error, p.distortion.mean_area_distortion,
                p.distortion.max_area_distortion, p.distortion.mean_angle_error_deg,
                p.distortion.max_angle_error_deg, p.vertices, p.triangles, p.min_angle_deg);
  for (const auto& s : b.seams)
    std::printf("  seam %-20s 3D %.4f m, sides %.4f / %.4f m (%.3f %%), %d vertices\n", s.name.c_str(),
                s.length_3d, s.length_a, s.length_b, 100 * s.relative_difference, s.vertices);
}

/// Checks shared by every garment: seams weld, maps round-trip, embedding is close.
void check_garment(const GarmentBuild& b, double max_projection) {
  const Garment& g = b.garment;
  for (const Seam& seam : g.pattern.seams) {
    ASSERT_EQ(seam.a.vertices.size(), seam.b.vertices.size()) << seam.name;
    for (size_t i = 0; i < seam.a.vertices.size(); ++i)
      EXPECT_EQ(g.pattern_to_garment[g.piece_offset[seam.a.piece] + seam.a.vertices[i]],
                g.pattern_to_garment[g.piece_offset[seam.b.piece] + seam.b.vertices[i]]);
  }
  // Piece → 3D panel → piece.
  double worst = 0.0;
  for (size_t k = 0; k < g.pattern.pieces.size(); ++k) {
    const PatternPiece& piece = g.pattern.pieces[k];
    for (Eigen::Index v = 0; v < piece.rest.rows(); v += 7) {
      const Vec2 q = piece.rest.row(v);
      const Vec3 p = piece_to_panel(b.layout, b.maps[k], q);
      worst = std::max(worst, (panel_to_piece(b.layout, b.maps[k], p) - q).norm());
    }
    // Triangles counter-clockwise.
    for (Eigen::Index f = 0; f < piece.triangles.rows(); ++f) {
      const Vec2 a = piece.rest.row(piece.triangles(f, 0)), c1 = piece.rest.row(piece.triangles(f, 1)),
                 c2 = piece.rest.row(piece.triangles(f, 2));
      EXPECT_GT((c1 - a).x() * (c2 - a).y() - (c1 - a).y() * (c2 - a).x(), 0.0);
    }
  }
  EXPECT_LT(worst, 1e-6);
  const double max_dist = *std::max_element(b.projection_distance.begin(), b.projection_distance.end());
  EXPECT_LT(max_dist, max_projection);
  EXPECT_EQ(static_cast<int>(g.embedding.size()), g.num_garment_vertices);
}

TEST(BuildGarment, SleeveOnCylinder) {
  const TriMesh body = test::closed_cylinder(0.05, 0.5, 32, 21);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 0.01;
  options.grain = Vec3::UnitY();
  options.scale = {0.95, 0.8};
  for (bool on_limit : {false, true}) {
    options.flatten_limit_surface = on_limit;
    const GarmentBuild b = build_garment(body, limit, spec_from(kSleeve), options);
    std::printf("sleeve, flattened on the %s:\n", on_limit ? "limit surface" : "control mesh");
    print_report(b);
    ASSERT_EQ(b.garment.pattern.pieces.size(), 2u);
    ASSERT_EQ(b.garment.pattern.seams.size(), 2u);
    for (const auto& p : b.pieces) {
      EXPECT_LT(p.distortion.area_error, 1e-3);
      EXPECT_EQ(p.distortion.flipped, 0);
    }
    check_garment(b, on_limit ? 5e-4 : 2e-3);  // chord sag of 1 cm edges at R = 5 cm: 0.25 mm
    // Grain along the cylinder: pieces are 0.3 · 0.95 m tall and half the circumference · 0.8 wide.
    for (const auto& piece : b.garment.pattern.pieces) {
      const Vec2 size = piece.rest.colwise().maxCoeff() - piece.rest.colwise().minCoeff();
      EXPECT_NEAR(size.y(), 0.3 * 0.95, 2e-3);
      EXPECT_NEAR(size.x(), 0.05 * test::kPi * 0.8, 4e-3);
    }
    // Both cuffs pinned: two pinned runs per piece.
    EXPECT_EQ(b.garment.pattern.pinned.size(), 4u);
    write_pattern_svg(std::string("/tmp/sleeve_") + (on_limit ? "limit" : "control") + ".svg", b.garment.pattern);
  }
}

}  // namespace
}  // namespace tightfit

namespace tightfit {
namespace {

const char* kSphereCover = R"({
  "region": [{"name": "opening", "point": [0, -0.07, 0], "normal": [0, 1, 0]}],
  "dividers": [{"name": "equator", "point": [0, 0, 0], "normal": [0, 1, 0]},
               {"name": "meridian", "point": [0, 0, 0], "normal": [1, 0, 0]}],
  "panels": [{"name": "top", "sides": ["+equator"]},
             {"name": "bottom_left", "sides": ["-equator", "-meridian"]},
             {"name": "bottom_right", "sides": ["-equator", "+meridian"]}],
  "pinned": [{"name": "opening", "on_plane": "opening"}],
  "seam_tolerance": 0.2
})";

TEST(BuildGarment, ThreePieceCoverOnSphere) {
  const TriMesh body = test::geodesic_sphere(0.1, 8);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 0.01;
  const GarmentBuild b = build_garment(body, limit, spec_from(kSphereCover), options);
  std::printf("sphere cover:\n");
  print_report(b);
  ASSERT_EQ(b.garment.pattern.pieces.size(), 3u);
  EXPECT_EQ(b.garment.pattern.seams.size(), 4u);
  check_garment(b, 5e-4);
  // A hemisphere cannot keep its rim length when flattened: the equator seams differ by
  // more than the default seam tolerance (5 %), hence the spec's 20 %.
  for (const auto& s : b.seams) {
    if (s.name.rfind("top/", 0) == 0) {
      EXPECT_GT(s.relative_difference, 0.05);
    }
  }
  auto j = nlohmann::json::parse(kSphereCover);
  j.erase("seam_tolerance");
  JsonFields f(j, "cover.json", "");
  const LayoutSpec strict = parse_layout_spec(f, "");
  try {
    build_garment(body, limit, strict, options);
    ADD_FAILURE() << "no error for mismatched seams";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cover.json: seam \"top/bottom_"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(seam_tolerance 5 %)"), std::string::npos) << e.what();
  }
}

TEST(BuildGarment, RejectsPanelsThatOverlapThemselvesWhenFlattened) {
  // A bag over the whole sphere but a small opening: flattening folds triangles over.
  const TriMesh body = test::geodesic_sphere(0.1, 6);
  const LimitSurface limit(body);
  const LayoutSpec spec = spec_from(R"({
    "region": [{"name": "opening", "point": [0, -0.098, 0], "normal": [0, 1, 0]}],
    "panels": [{"name": "bag"}]})", "bag.json");
  PatternOptions options;
  options.flatten_limit_surface = false;
  try {
    build_garment(body, limit, spec, options);
    ADD_FAILURE() << "no error for a folded flattening";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bag.json: panel \"bag\" overlaps itself when flattened"),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tightfit
