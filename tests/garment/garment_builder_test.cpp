#include "tightfit/garment/garment_builder.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cstdio>
#include <iterator>

#include "garment/garment_test_meshes.hpp"
#include "garment/panel_mapping.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit::garment_builder_test {

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
    std::printf(
        "  piece %-12s area err %.2e  mean |J|-1 %.2e  max %.2e  angle mean %.3f max %.3f deg  "
        "%d verts %d tris, min angle %.1f\n",
        p.name.c_str(), p.distortion.area_error, p.distortion.mean_area_distortion,
        p.distortion.max_area_distortion, p.distortion.mean_angle_error_deg,
        p.distortion.max_angle_error_deg, p.vertices, p.triangles, p.min_angle_deg);
  for (const auto& s : b.seams)
    std::printf("  seam %-20s 3D %.4f m, sides %.4f / %.4f m (%.3f %%), %d vertices\n",
                s.name.c_str(), s.length_3d, s.length_a, s.length_b, 100 * s.relative_difference,
                s.vertices);
}

/// Checks shared by every garment: seams weld, maps round-trip, embedding is close.
void check_garment(const GarmentBuild& b, double max_projection) {
  const Garment& g = b.garment;
  for (const Seam& seam : g.pattern.seams) {
    ASSERT_EQ(seam.a.vertices.size(), seam.b.vertices.size()) << seam.name;
    for (size_t i = 0; i < seam.a.vertices.size(); ++i)
      EXPECT_EQ(
          g.topology
              ->pattern_to_garment[g.topology->piece_offset[seam.a.piece] + seam.a.vertices[i]],
          g.topology
              ->pattern_to_garment[g.topology->piece_offset[seam.b.piece] + seam.b.vertices[i]]);
  }
  // Piece → 3D panel → piece.
  double worst = 0.0;
  for (size_t k = 0; k < g.pattern.pieces.size(); ++k) {
    const PatternPiece& piece = g.pattern.pieces[k];
    for (Eigen::Index v = 0; v < piece.rest.rows(); v += 7) {
      const Vec2 q = piece.rest.row(v);
      const Vec3 p = test::piece_to_panel(b.layout, b.maps[k], q);
      worst = std::max(worst, (test::panel_to_piece(b.layout, b.maps[k], p) - q).norm());
    }
    // Triangles counter-clockwise.
    for (Eigen::Index f = 0; f < piece.triangles.rows(); ++f) {
      const Vec2 a = piece.rest.row(piece.triangles(f, 0)),
                 c1 = piece.rest.row(piece.triangles(f, 1)),
                 c2 = piece.rest.row(piece.triangles(f, 2));
      EXPECT_GT((c1 - a).x() * (c2 - a).y() - (c1 - a).y() * (c2 - a).x(), 0.0);
    }
  }
  EXPECT_LT(worst, 1e-6);
  const double max_dist =
      *std::max_element(b.projection_distance.begin(), b.projection_distance.end());
  EXPECT_LT(max_dist, max_projection);
  EXPECT_EQ(static_cast<int>(g.embedding.size()), g.num_garment_vertices());
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
  }
}

}  // namespace tightfit::garment_builder_test

namespace tightfit::garment_builder_test {

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

TEST(BuildGarment, SleeveOnTheGeneratedCapsule) {
  // The body layer's capsule: staggered rings, control points fitted so that the limit
  // surface lies on the analytic cylinder. Panels flattened on the limit surface.
  CylinderParams params;
  params.radius = 0.05;
  params.length = 0.4;
  params.axis = Vec3::UnitY();
  params.center = Vec3(0, 0.25, 0);
  const TriMesh body = cylinder_surface(params);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 0.01;
  options.grain = Vec3::UnitY();
  const GarmentBuild b = build_garment(body, limit, spec_from(kSleeve), options);
  std::printf("sleeve on the generated capsule:\n");
  print_report(b);
  ASSERT_EQ(b.garment.pattern.pieces.size(), 2u);
  for (const auto& p : b.pieces) {
    EXPECT_LT(p.distortion.area_error, 1e-3) << p.name;
    EXPECT_LT(p.distortion.mean_area_distortion, 1e-3) << p.name;
  }
  check_garment(b, 5e-4);
  // The garment lies on the analytic cylinder (the fitted limit surface).
  for (Eigen::Index v = 0; v < b.positions.rows(); ++v)
    EXPECT_NEAR(std::hypot(b.positions(v, 0), b.positions(v, 2)), 0.05, 2e-4);
  // Pinned: exactly the two cuff rings, at y = 0.1 and 0.4.
  ASSERT_FALSE(b.garment.topology->pinned.empty());
  for (int v : b.garment.topology->pinned) {
    const double y = b.positions(v, 1);
    EXPECT_LT(std::min(std::abs(y - 0.1), std::abs(y - 0.4)), 1e-9);
  }
  int on_cuffs = 0;
  for (Eigen::Index v = 0; v < b.positions.rows(); ++v)
    on_cuffs +=
        std::min(std::abs(b.positions(v, 1) - 0.1), std::abs(b.positions(v, 1) - 0.4)) < 1e-9;
  EXPECT_EQ(on_cuffs, static_cast<int>(b.garment.topology->pinned.size()));
  // Garment triangles face outward.
  const Triangles& t = b.garment.topology->garment_triangles;
  for (Eigen::Index f = 0; f < t.rows(); ++f) {
    const Vec3 p0 = b.positions.row(t(f, 0)), p1 = b.positions.row(t(f, 1)),
               p2 = b.positions.row(t(f, 2));
    const Vec3 c = (p0 + p1 + p2) / 3.0;
    EXPECT_GT((p1 - p0).cross(p2 - p0).dot(Vec3(c.x(), 0, c.z())), 0.0);
  }
}

TEST(BuildGarment, APatternEdgeTooShortToMeshIsAnErrorBeforeMeshing) {
  SphereParams params;
  params.radius = 0.1;
  const TriMesh body = sphere_surface(params);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 1e-5;  // 0.01 mm: "0.01" meant in mm
  try {
    build_garment(body, limit, spec_from(kSphereCover, "cover.json"), options);
    ADD_FAILURE() << "no error for a 0.01 mm pattern edge";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "cover.json: pattern: an edge length of 1e-05 m would mesh the pattern pieces"),
              std::string::npos)
        << e.what();
  }
}

TEST(BuildGarment, ThreePieceCoverOnSphere) {
  SphereParams params;
  params.radius = 0.1;
  const TriMesh body = sphere_surface(params);
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
    EXPECT_NE(std::string(e.what()).find("cover.json: seam \"top/bottom_"), std::string::npos)
        << e.what();
    EXPECT_NE(
        std::string(e.what()).find("(seam_tolerance 5 %, and more than the pattern edge length)"),
        std::string::npos)
        << e.what();
  }
}

TEST(BuildGarment, RejectsPanelsTooCurvedToFlatten) {
  // A bag over the whole sphere but a small opening: no flat piece has its shape (the
  // flattening stops before it folds triangles over, far from its 3D area).
  const TriMesh body = test::geodesic_sphere(0.1, 6);
  const LimitSurface limit(body);
  const LayoutSpec spec = spec_from(R"({
    "region": [{"name": "opening", "point": [0, -0.098, 0], "normal": [0, 1, 0]}],
    "panels": [{"name": "bag"}]})",
                                    "bag.json");
  PatternOptions options;
  options.flatten_limit_surface = false;
  try {
    build_garment(body, limit, spec, options);
    ADD_FAILURE() << "no error for a bag flattened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "bag.json: panel \"bag\" is too curved to flatten: its flat area differs "
                  "from its area on the body by "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("(area_tolerance 50 %)"), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::garment_builder_test

namespace tightfit::garment_builder_test {

/// Writes the layout's panels as an OBJ with one group per panel over shared vertices.
void write_layout_obj(const std::string& file, const Layout& layout) {
  ObjGroups obj;
  obj.mesh = layout.surface;
  obj.face_group = layout.face_panel;
  for (const auto& p : layout.panels) obj.group_names.push_back(p.name);
  write_obj_with_groups(file, obj);
}

/// Writes the rules layout as an OBJ the way Blender exports separate objects: every
/// panel with its own copies of the vertices.
void write_blender_style_obj(const std::string& file, const Layout& layout) {
  ObjGroups obj;
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  for (size_t p = 0; p < layout.panels.size(); ++p) {
    const LayoutPanel& panel = layout.panels[p];
    const int base = static_cast<int>(v.size());
    for (int i = 0; i < panel.mesh.num_vertices(); ++i)
      v.push_back(panel.mesh.vertices.row(i).transpose());
    for (int t = 0; t < panel.mesh.num_faces(); ++t) {
      f.push_back({base + panel.mesh.faces(t, 0), base + panel.mesh.faces(t, 1),
                   base + panel.mesh.faces(t, 2)});
      obj.face_group.push_back(static_cast<int>(p));
    }
    obj.group_names.push_back(panel.name);
  }
  obj.mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i)
    obj.mesh.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  obj.mesh.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (size_t i = 0; i < f.size(); ++i)
    obj.mesh.faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  write_obj_with_groups(file, obj);
}

TEST(BuildGarment, ObjGroupLayoutGivesTheSamePiecesAsTheRules) {
  const TriMesh body = test::closed_cylinder(0.05, 0.5, 32, 21);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 0.01;
  options.flatten_limit_surface = false;  // identical panels in, identical pieces out
  const LayoutSpec rules = spec_from(kSleeve);
  const GarmentBuild a = build_garment(body, limit, rules, options);

  const std::string dir = ::testing::TempDir();
  write_layout_obj(dir + "/sleeve_layout.obj", a.layout);
  write_blender_style_obj(dir + "/sleeve_blender.obj", a.layout);
  for (const char* file : {"sleeve_layout.obj", "sleeve_blender.obj"}) {
    auto j = nlohmann::json::parse(R"({"pinned": [
        {"name": "cuff", "on_plane": {"point": [0, 0.1, 0], "normal": [0, 1, 0]}},
        {"name": "top", "nearest": [0.05, 0.41, 0]}]})");
    j["mesh"] = file;
    JsonFields f(j, dir + "/sleeve.json", "");
    const GarmentBuild b = build_garment(body, limit, parse_layout_spec(f, dir), options);
    ASSERT_EQ(b.garment.pattern.pieces.size(), a.garment.pattern.pieces.size()) << file;
    for (size_t k = 0; k < a.garment.pattern.pieces.size(); ++k) {
      const PatternPiece& pa = a.garment.pattern.pieces[k];
      const PatternPiece& pb = b.garment.pattern.pieces[k];
      EXPECT_EQ(pa.name, pb.name);
      ASSERT_EQ(pa.rest.rows(), pb.rest.rows()) << file;
      ASSERT_EQ(pa.triangles.rows(), pb.triangles.rows()) << file;
      EXPECT_LT((pa.rest - pb.rest).cwiseAbs().maxCoeff(), 1e-9) << file;
      EXPECT_TRUE(pa.triangles == pb.triangles) << file;
      EXPECT_EQ(pa.corners, pb.corners) << file;
    }
    ASSERT_EQ(b.garment.pattern.seams.size(), a.garment.pattern.seams.size());
    for (size_t s = 0; s < a.garment.pattern.seams.size(); ++s)
      EXPECT_EQ(a.garment.pattern.seams[s].a.vertices, b.garment.pattern.seams[s].a.vertices);
    EXPECT_EQ(b.garment.topology->pinned, a.garment.topology->pinned) << file;
    EXPECT_EQ(b.garment.num_garment_vertices(), a.garment.num_garment_vertices());
    EXPECT_LT((b.positions - a.positions).cwiseAbs().maxCoeff(), 1e-9);
  }
}

}  // namespace tightfit::garment_builder_test

namespace tightfit::garment_builder_test {

TEST(BuildGarment, KeepsSharpTurnsOfOpenBoundariesAsCorners) {
  // The sleeve's upper edge is cut by two planes meeting at x = 0: a 45° turn in the
  // middle of each piece's open upper boundary.
  const TriMesh body = test::closed_cylinder(0.05, 0.5, 32, 21);
  const LimitSurface limit(body);
  const LayoutSpec spec = spec_from(R"({
    "region": [{"name": "bottom", "point": [0, 0.1, 0], "normal": [0, 1, 0]},
               {"name": "top", "point": [0, 0.4, 0], "normal": [0, -1, 0]},
               {"name": "slant", "point": [0, 0.4, 0], "normal": [-1, -1, 0]}],
    "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [0, 0, 1]}],
    "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}]})");
  PatternOptions options;
  options.edge_length = 0.01;
  options.flatten_limit_surface = false;
  const GarmentBuild b = build_garment(body, limit, spec, options);
  for (size_t k = 0; k < 2; ++k) {
    const PatternPiece& piece = b.garment.pattern.pieces[k];
    // Four seam ends and the turn.
    ASSERT_EQ(piece.corners.size(), 5u) << piece.name;
    int at_turn = 0;
    for (int c : piece.corners) {
      const Vec3 x = panel_position(b.layout, b.maps[k], b.maps[k].location[c]);
      if (std::abs(x.x()) < 1e-9 && std::abs(x.y() - 0.4) < 1e-9) ++at_turn;
    }
    EXPECT_EQ(at_turn, 1) << piece.name;
  }
  options.corner_angle_deg = 60;  // a 45° turn is then no corner
  const GarmentBuild smooth = build_garment(body, limit, spec, options);
  EXPECT_EQ(smooth.garment.pattern.pieces[0].corners.size(), 4u);
}

}  // namespace tightfit::garment_builder_test
