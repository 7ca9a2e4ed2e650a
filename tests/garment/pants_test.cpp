#include <gtest/gtest.h>

#include <filesystem>

#include <cstdio>

#include "garment/panel_mapping.hpp"
#include "tightfit/body/surface_remeshing.hpp"
#include "tightfit/garment/garment_builder.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::pants_test {

/// Pants on the legs body (y up, front +z, left leg +x): waist at 1.0 m, cuffs at 0.15 m,
/// left/right by the sagittal plane, front/back by a coronal plane; pants8 adds a knee
/// divider. The specs are in tests/garment/data (examples for `tightfit layout`).
std::string spec_file(const char* name) {
  return (std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "tests/garment/data" / name).string();
}

class Pants : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    body_ = new TriMesh(
        read_tri_mesh(std::filesystem::path(TIGHTFIT_DATA_DIR) / "bodies/mh_legs_male.obj"));
    limit_ = new LimitSurface(*body_);
  }
  static void TearDownTestSuite() {
    delete limit_;
    delete body_;
  }

  static GarmentBuild build(const char* spec) { return build_on(*body_, *limit_, spec); }

  static GarmentBuild build_on(const TriMesh& body, const LimitSurface& limit, const char* spec) {
    PatternOptions options;
    options.edge_length = 0.02;
    options.grain = Vec3::UnitY();
    options.scale = {0.95, 0.77};  // ~30 % stretch around the legs
    return build_garment(body, limit, read_layout_spec(spec_file(spec)), options);
  }

  static void report(const GarmentBuild& b) {
    for (const auto& p : b.pieces)
      std::printf(
          "  %-18s area error %.2e, |det J - 1| mean %.2e max %.2e, angle error mean %.2f max %.1f "
          "deg, "
          "%d vertices, min angle %.1f deg\n",
          p.name.c_str(), p.distortion.area_error, p.distortion.mean_area_distortion,
          p.distortion.max_area_distortion, p.distortion.mean_angle_error_deg,
          p.distortion.max_angle_error_deg, p.vertices, p.min_angle_deg);
    for (const auto& s : b.seams)
      std::printf("  seam %-36s 3D %.4f m, sides %.4f / %.4f m (%.2f %%), %d vertices\n",
                  s.name.c_str(), s.length_3d, s.length_a, s.length_b, 100 * s.relative_difference,
                  s.vertices);
  }

  static void check(const GarmentBuild& b, double max_seam_difference) {
    const Garment& g = b.garment;
    for (const Seam& seam : g.pattern.seams) {
      ASSERT_EQ(seam.a.vertices.size(), seam.b.vertices.size());
      for (size_t i = 0; i < seam.a.vertices.size(); ++i)
        EXPECT_EQ(
            g.topology
                ->pattern_to_garment[g.topology->piece_offset[seam.a.piece] + seam.a.vertices[i]],
            g.topology
                ->pattern_to_garment[g.topology->piece_offset[seam.b.piece] + seam.b.vertices[i]]);
    }
    for (const auto& p : b.pieces) {
      EXPECT_EQ(p.distortion.flipped, 0);
      EXPECT_LT(p.distortion.mean_area_distortion, 0.05) << p.name;
      EXPECT_LT(p.distortion.mean_angle_error_deg, 2.0) << p.name;
      EXPECT_GT(p.min_angle_deg, 20.0) << p.name;
    }
    for (const auto& s : b.seams) EXPECT_LT(s.relative_difference, max_seam_difference) << s.name;
    // Garment vertices on the limit surface, at most the chord sag of 2 cm edges away
    // from the piecewise-flat panels (2-3 cm body edges at 5 cm radius: ~2 mm).
    EXPECT_LT(*std::max_element(b.projection_distance.begin(), b.projection_distance.end()), 5e-3);
    // Both cuffs and the waistband are pinned, on every piece that reaches them.
    EXPECT_FALSE(g.topology->pinned.empty());
    // Piece → 3D panel → piece.
    double worst = 0.0;
    for (size_t k = 0; k < g.pattern.pieces.size(); ++k)
      for (Eigen::Index v = 0; v < g.pattern.pieces[k].rest.rows(); v += 5) {
        const Vec2 q = g.pattern.pieces[k].rest.row(v);
        worst =
            std::max(worst, (test::panel_to_piece(b.layout, b.maps[k],
                                                  test::piece_to_panel(b.layout, b.maps[k], q)) -
                             q)
                                .norm());
      }
    EXPECT_LT(worst, 1e-6);
  }

  static TriMesh* body_;
  static LimitSurface* limit_;
};

TriMesh* Pants::body_ = nullptr;
LimitSurface* Pants::limit_ = nullptr;

TEST_F(Pants, FourPiecesOnTheLegsBody) {
  const GarmentBuild b = build("pants4.json");
  std::printf("4-piece pants on mh_legs_male:\n");
  report(b);
  ASSERT_EQ(b.garment.pattern.pieces.size(), 4u);
  // Centre front, centre back, and per leg the inseam and the outseam.
  EXPECT_EQ(b.garment.pattern.seams.size(), 6u);
  // Waistband and cuff on every piece.
  EXPECT_EQ(b.garment.pattern.pinned.size(), 8u);
  check(b, 0.005);
  // The four pieces meet at the crotch: one garment vertex shared by four pattern vertices.
  std::vector<int> uses(b.garment.num_garment_vertices(), 0);
  for (int v : b.garment.topology->pattern_to_garment) ++uses[v];
  EXPECT_EQ(*std::max_element(uses.begin(), uses.end()), 4);
}

TEST_F(Pants, EightPiecesWithAKneeDivider) {
  const GarmentBuild b = build("pants8.json");
  std::printf("8-piece pants on mh_legs_male:\n");
  report(b);
  ASSERT_EQ(b.garment.pattern.pieces.size(), 8u);
  // 6 seams of the 4-piece pants, each leg seam split at the knee (+4), and 4 knee seams.
  EXPECT_EQ(b.garment.pattern.seams.size(), 14u);
  check(b, 0.05);  // the knee seams at the back (hollow of the knee) differ by ~4 %
}

TEST_F(Pants, FourPiecesOnTheRemeshedLegsBody) {
  // The simulation body: the legs remeshed isotropically by the body layer.
  RemeshOptions remesh;
  remesh.edge_length = 0.02;
  const TriMesh body = remesh_isotropic(*body_, remesh).mesh;
  const LimitSurface limit(body);
  const GarmentBuild b = build_on(body, limit, "pants4.json");
  std::printf("4-piece pants on mh_legs_male remeshed at 2 cm (%d faces):\n", body.num_faces());
  report(b);
  ASSERT_EQ(b.garment.pattern.pieces.size(), 4u);
  EXPECT_EQ(b.garment.pattern.seams.size(), 6u);
  check(b, 0.01);
}

}  // namespace tightfit::pants_test
