// Openings (holes in pattern pieces, e.g. a mask's eyes): the layout's ellipsoid cuts,
// flattening and meshing with holes, and the pieces the pattern builder makes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "garment/garment_test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/garment/flatten.hpp"
#include "tightfit/garment/garment_builder.hpp"
#include "tightfit/garment/layout.hpp"
#include "tightfit/garment/piece_mesher.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace openings_test {

LayoutSpec parse_spec(const nlohmann::json& j, const std::string& source = "openings.json") {
  JsonFields f(j, source, "");
  return parse_layout_spec(f, "");
}

/// A sleeve (front and back panels) on a closed cylinder of radius 0.05 m, y ∈ [0, 0.4],
/// with one opening on the front panel: a sphere of radius 0.015 m centred on the
/// surface at (0.05, 0.2, 0).
nlohmann::json sleeve_with_opening() {
  return nlohmann::json::parse(R"({
    "region": [{"name": "bottom", "point": [0, 0.05, 0], "normal": [0, 1, 0]},
               {"name": "top", "point": [0, 0.35, 0], "normal": [0, -1, 0]}],
    "dividers": [{"name": "side", "point": [0, 0, 0], "normal": [1, 0, 0]}],
    "panels": [{"name": "front", "sides": ["+side"]}, {"name": "back", "sides": ["-side"]}],
    "openings": [{"name": "window", "center": [0.05, 0.2, 0], "radius": 0.015}],
    "pinned": [{"name": "cuff", "on_plane": "bottom"}]
  })");
}

std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

double signed_area(const Points2& x, const std::vector<int>& loop) {
  return polygon_signed_area(loop.size(),
                             [&](size_t i) -> Vec2 { return x.row(loop[i]).transpose(); });
}

bool inside(const Points2& x, const std::vector<int>& loop, const Vec2& q) {
  return inside_polygon(
      loop.size(), [&](size_t i) -> Vec2 { return x.row(loop[i]); }, q);
}

TEST(Openings, ParseWithRadiusOrRadiiAndRejectBadOnes) {
  const LayoutSpec spec = parse_spec(sleeve_with_opening());
  ASSERT_EQ(spec.openings.size(), 1u);
  EXPECT_EQ(spec.openings[0].name, "window");
  EXPECT_TRUE(spec.openings[0].radii.isApprox(Vec3::Constant(0.015)));
  EXPECT_EQ(spec.openings[0].source_path, "/openings/0");
  auto j = sleeve_with_opening();
  j["openings"][0].erase("radius");
  j["openings"][0]["radii"] = {0.02, 0.01, 0.03};
  EXPECT_TRUE(parse_spec(j).openings[0].radii.isApprox(Vec3(0.02, 0.01, 0.03)));
  j["openings"][0]["radii"] = {0.02, 0.0, 0.03};
  EXPECT_NE(input_error_of([&] {
              parse_spec(j);
            }).find("/openings/0/radii: every semi-axis must be positive"),
            std::string::npos);
  j["openings"][0]["radius"] = 0.01;
  EXPECT_NE(input_error_of([&] { parse_spec(j); }).find("exactly one of \"radius\" and \"radii\""),
            std::string::npos);
  auto twice = sleeve_with_opening();
  twice["openings"].push_back(twice["openings"][0]);
  EXPECT_NE(input_error_of([&] { parse_spec(twice); }).find("duplicate opening name \"window\""),
            std::string::npos);
  // A level function: zero on the ellipsoid, negative inside, about the distance near it.
  LayoutOpening e;
  e.center = Vec3(1, 2, 3);
  e.radii = Vec3(0.1, 0.2, 0.3);
  EXPECT_NEAR(e.level(Vec3(1.1, 2, 3)), 0.0, 1e-15);
  EXPECT_NEAR(e.level(Vec3(1, 2.2, 3)), 0.0, 1e-15);
  EXPECT_LT(e.level(e.center + Vec3(0.05, 0, 0)), 0.0);
  EXPECT_NEAR(e.level(Vec3(1.101, 2, 3)), 0.001, 1e-12);
}

TEST(Openings, CutAHoleWhoseRimLiesOnTheEllipsoid) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 48, 41);
  const LayoutSpec spec = parse_spec(sleeve_with_opening());
  const Layout layout = layout_from_rules(body, spec);
  ASSERT_EQ(layout.panels.size(), 2u);
  const LayoutPanel& front = layout.panels[0];
  const LayoutPanel& back = layout.panels[1];
  EXPECT_TRUE(back.holes.empty());
  ASSERT_EQ(front.holes.size(), 1u);
  EXPECT_EQ(front.holes[0].pin, -1);  // a free rim
  const LayoutOpening& window = spec.openings[0];
  double rim_length = 0.0;
  const std::vector<int>& loop = front.holes[0].loop;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec3 p = front.mesh.vertices.row(loop[i]);
    EXPECT_NEAR((p - window.center).norm(), 0.015, 1e-12);
    rim_length +=
        (front.mesh.vertices.row(loop[(i + 1) % loop.size()]) - front.mesh.vertices.row(loop[i]))
            .norm();
  }
  // A circle of radius ≈ 0.015 m on a cylinder of radius 0.05 m.
  EXPECT_NEAR(rim_length, 2 * test::kPi * 0.015, 0.05 * 2 * test::kPi * 0.015);
  // The outer loop is the panel's outline (seams and cuffs), not the rim.
  for (int v : front.boundary)
    EXPECT_GT(std::abs((Vec3(front.mesh.vertices.row(v)) - window.center).norm() - 0.015), 1e-6);
  // The rim can be pinned with "nearest".
  auto j = sleeve_with_opening();
  j["pinned"].push_back({{"name", "rim"}, {"nearest", {0.05, 0.2, 0.0}}});
  const Layout pinned = layout_from_rules(body, parse_spec(j));
  ASSERT_EQ(pinned.panels[0].holes.size(), 1u);
  EXPECT_EQ(pinned.pin_names[static_cast<size_t>(pinned.panels[0].holes[0].pin)], "rim");
}

TEST(Openings, AreRejectedWhenTheyCutNothingAndBandsStillNeedADivider) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 32, 21);
  auto j = sleeve_with_opening();
  j["openings"][0]["center"] = {0.5, 0.2, 0.0};
  const std::string missed = input_error_of([&] { layout_from_rules(body, parse_spec(j)); });
  EXPECT_NE(missed.find("openings.json: /openings/0: opening \"window\" cuts nothing"),
            std::string::npos)
      << missed;
  // An opening on the region's edge makes a notch in the outline, not a hole.
  auto notch = sleeve_with_opening();
  notch["openings"][0]["center"] = {0.05, 0.05, 0.0};
  const Layout layout = layout_from_rules(body, parse_spec(notch));
  EXPECT_TRUE(layout.panels[0].holes.empty());
  // One panel around the cylinder is a band, whatever the openings.
  auto tube = sleeve_with_opening();
  tube.erase("dividers");
  tube["panels"] = nlohmann::json::parse(R"([{"name": "tube"}])");
  const std::string band = input_error_of([&] { layout_from_rules(body, parse_spec(tube)); });
  EXPECT_NE(band.find("panel \"tube\" is not a disc: it has 3 boundary loops"), std::string::npos)
      << band;
  EXPECT_NE(band.find("not made by an opening (a band around the body? add a divider)"),
            std::string::npos)
      << band;
}

TEST(Openings, MesherKeepsHolesEmptyAndRejectsBadHoles) {
  // A 1 m square with a square hole of 0.4 m in its middle.
  const double h = 0.05;
  auto square = [&](double lo, double hi, bool clockwise) {
    std::vector<Vec2> corners{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}};
    if (clockwise) std::reverse(corners.begin(), corners.end());
    std::vector<Vec2> pts;
    for (size_t i = 0; i < 4; ++i) {
      const Vec2 a = corners[i], b = corners[(i + 1) % 4];
      const int n = static_cast<int>(std::lround((b - a).norm() / h));
      for (int k = 0; k < n; ++k) pts.push_back(a + (b - a) * k / n);
    }
    Points2 p(static_cast<Eigen::Index>(pts.size()), 2);
    for (size_t i = 0; i < pts.size(); ++i)
      p.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
    return p;
  };
  const Points2 outer = square(0, 1, false), hole = square(0.3, 0.7, true);
  const PieceMesh m = mesh_piece(outer, {hole}, h);
  EXPECT_TRUE(m.vertices.topRows(outer.rows()) == outer);
  EXPECT_TRUE(m.vertices.middleRows(outer.rows(), hole.rows()) == hole);
  double area = 0.0;
  for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
    const Vec2 a = m.vertices.row(m.triangles(f, 0)), b = m.vertices.row(m.triangles(f, 1)),
               c = m.vertices.row(m.triangles(f, 2));
    const double a2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    EXPECT_GT(a2, 0.0);
    area += 0.5 * a2;
    const Vec2 centroid = (a + b + c) / 3.0;
    EXPECT_FALSE(centroid.x() > 0.3 && centroid.x() < 0.7 && centroid.y() > 0.3 &&
                 centroid.y() < 0.7);
  }
  EXPECT_NEAR(area, 1.0 - 0.16, 1e-12);
  EXPECT_GT(min_angle_deg(m.vertices, m.triangles), 25.0);
  const SurfaceTopology topo(m.triangles, static_cast<int>(m.vertices.rows()));
  EXPECT_EQ(topo.boundary_loops().size(), 2u);
  EXPECT_TRUE(topo.isolated_vertices().empty());
  auto error_of = [&](const std::vector<Points2>& holes) {
    try {
      mesh_piece(outer, holes, h);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of({square(0.3, 0.7, false)}).find("hole 1 is not clockwise"), std::string::npos);
  EXPECT_NE(error_of({square(1.3, 1.7, true)}).find("hole 1 is not inside the outer boundary"),
            std::string::npos);
  const std::string crossing = error_of({hole, square(0.52, 0.92, true)});
  EXPECT_NE(crossing.find("crosses itself"), std::string::npos) << crossing;
}

TEST(Openings, FlattenAPlanarAnnulusIsometricallyAndFindOpeningsOutside) {
  // A flat square plate with a square hole, in the plane z = 0.
  const int n = 11;
  TriMesh plate;
  plate.vertices.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) plate.vertices.row(i * n + k) << 0.1 * k, 0.1 * i, 0.0;
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i + 1 < n; ++i)
    for (int k = 0; k + 1 < n; ++k) {
      if (i == 5 && k == 5) continue;  // the hole: one cell
      const int a = i * n + k, b = a + 1, c = a + n, d = c + 1;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  plate.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      plate.faces(static_cast<Eigen::Index>(f), c) = faces[f][static_cast<size_t>(c)];
  const SurfaceTopology topo(plate.faces, plate.num_vertices());
  auto loops = topo.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  if (loops[0].size() < loops[1].size()) std::swap(loops[0], loops[1]);
  const Flattening flat = flatten_panel(plate, loops);
  EXPECT_LT(flat.report.area_error, 1e-9);
  EXPECT_LT(flat.report.max_angle_error_deg, 1e-6);
  EXPECT_EQ(find_overlap(plate, loops, flat.uv), "");
  // The same loops with the roles swapped: the "hole" lies outside the "outer" loop.
  EXPECT_NE(find_overlap(plate, {loops[1], loops[0]}, flat.uv).find("an opening lies outside"),
            std::string::npos);
}

TEST(Openings, BuildPiecesWithClockwiseHolesThatSurviveTheWholeBuild) {
  const TriMesh body = test::closed_cylinder(0.05, 0.4, 48, 41);
  const LimitSurface limit(body);
  PatternOptions options;
  options.edge_length = 0.008;
  options.grain = Vec3::UnitY();
  options.scale = {1.0, 1.0};
  auto j = sleeve_with_opening();
  j["pinned"].push_back({{"name", "rim"}, {"nearest", {0.05, 0.2, 0.0}}});
  const GarmentBuild b = build_garment(body, limit, parse_spec(j), options);
  const Pattern& pattern = b.garment.pattern;
  ASSERT_EQ(pattern.pieces.size(), 2u);
  const PatternPiece& front = pattern.pieces[0];
  ASSERT_EQ(front.holes.size(), 1u);
  EXPECT_TRUE(pattern.pieces[1].holes.empty());
  const std::vector<int>& hole = front.holes[0];
  // About 2π · 15 mm / 8 mm edges, clockwise, inside the outline, no triangle inside.
  EXPECT_NEAR(static_cast<double>(hole.size()), 2 * test::kPi * 0.015 / 0.008, 2.0);
  EXPECT_LT(signed_area(front.rest, hole), 0.0);
  EXPECT_NEAR(-signed_area(front.rest, hole), test::kPi * 0.015 * 0.015,
              0.1 * test::kPi * 0.015 * 0.015);
  for (int v : hole) EXPECT_TRUE(inside(front.rest, front.boundary, front.rest.row(v)));
  for (Eigen::Index f = 0; f < front.triangles.rows(); ++f) {
    const Vec2 c = (front.rest.row(front.triangles(f, 0)) + front.rest.row(front.triangles(f, 1)) +
                    front.rest.row(front.triangles(f, 2))) /
                   3.0;
    EXPECT_FALSE(inside(front.rest, hole, c));
  }
  // Piece area = panel area (the cylinder is developable; the pattern is not scaled).
  double area = 0.0;
  for (Eigen::Index f = 0; f < front.triangles.rows(); ++f) {
    const Vec2 a = front.rest.row(front.triangles(f, 0)),
               c1 = front.rest.row(front.triangles(f, 1)),
               c2 = front.rest.row(front.triangles(f, 2));
    area += 0.5 * ((c1 - a).x() * (c2 - a).y() - (c1 - a).y() * (c2 - a).x());
  }
  EXPECT_NEAR(area, test::kPi * 0.05 * 0.3 - test::kPi * 0.015 * 0.015, 0.02 * area);
  // The rim's pin holds the hole's vertices; the garment embeds every hole vertex.
  bool found = false;
  for (const PinnedBoundary& pin : pattern.pinned)
    if (pin.name == "rim") {
      found = true;
      EXPECT_EQ(pin.piece, 0);
      EXPECT_EQ(pin.vertices, hole);
    }
  EXPECT_TRUE(found);
  for (int v : hole) {
    const int g =
        b.garment.topology
            ->pattern_to_garment[static_cast<size_t>(b.garment.topology->piece_offset[0] + v)];
    EXPECT_NEAR((Vec3(b.positions.row(g)) - Vec3(0.05, 0.2, 0.0)).norm(), 0.015, 1e-3);
  }
}

}  // namespace openings_test
}  // namespace tightfit
