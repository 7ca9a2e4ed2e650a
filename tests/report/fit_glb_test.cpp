#include "tightfit/report/fit_glb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "report/support/fit_test_tools.hpp"
#include "report/support/fit_test_view.hpp"
#include "tightfit/body/body_spec.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/scene/body_up.hpp"

namespace tightfit::fit_glb_test {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(i)]);
  return v;
}

/// The JSON chunk of a .glb (checks the header and chunk layout on the way).
nlohmann::json glb_json(const std::string& bytes) {
  EXPECT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(u32_at(bytes, 4), 2u);
  EXPECT_EQ(u32_at(bytes, 8), bytes.size());
  const std::uint32_t json_length = u32_at(bytes, 12);
  EXPECT_EQ(json_length % 4, 0u);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  const std::size_t bin = 20 + json_length;
  EXPECT_EQ(bytes.substr(bin + 4, 4), std::string("BIN\0", 4));
  EXPECT_EQ(bin + 8 + u32_at(bytes, bin), bytes.size());
  return nlohmann::json::parse(bytes.substr(20, json_length));
}

TEST(FitGlb, PassesTheKhronosValidator) {
  test::TempDir dir("glb");
  const FitView view = test::band_on_sphere(16, 4);
  GlbOptions options;
  options.coloring = standard_colorings()[2];  // pressure in mmHg, turbo
  const ResolvedColoring used = write_fit_glb(dir / "fit.glb", view, options);
  EXPECT_LT(used.lo, 0.0);  // lift-off kept in the range
  EXPECT_NEAR(used.hi, 2800.0 / kPascalPerMmHg, 0.2);

  const auto result = test::run_command(
      "node " + test::shell_quote(test::source_path("tests/report/fit_glb_validate.mjs")) + " " +
          test::shell_quote(dir / "fit.glb"),
      dir / "validator.log");
  ASSERT_EQ(result.exit_code, 0) << "gltf-validator (node, report/node_modules; see "
                                 << "scripts/install-deps.sh) reported errors or could not run:\n"
                                 << result.output;
  const auto report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["numErrors"], 0) << result.output;
  EXPECT_EQ(report["numWarnings"], 0) << result.output;
  // The body and the garment, and a garment per further map (min stretch, pressure,
  // regime): the map scenes draw the same geometry with their colours.
  EXPECT_EQ(report["info"]["drawCallCount"], 2 + 3) << result.output;
}

TEST(FitGlb, APoseIsANodeWithItsPosedBodyAndGarmentInASceneOfItsOwn) {
  test::TempDir dir("glb_pose");
  FitView view = test::band_on_sphere(16, 4);
  FitPose pose;
  pose.name = "raised";
  pose.garment = view.garment.vertices;
  pose.garment.col(1).array() += 0.05;
  pose.garment_normals = Points3::Zero(view.garment.vertices.rows(), 3);
  pose.body = view.body.vertices;
  pose.body.col(1).array() += 0.05;
  pose.sliding_excess = VecX::LinSpaced(view.garment.num_faces(), 0.0, 1.5);
  view.poses = {pose};
  write_fit_glb(dir / "fit.glb", view);
  const auto result = test::run_command(
      "node " + test::shell_quote(test::source_path("tests/report/fit_glb_validate.mjs")) + " " +
          test::shell_quote(dir / "fit.glb"),
      dir / "validator.log");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["numErrors"], 0) << result.output;
  EXPECT_EQ(report["numWarnings"], 0) << result.output;
  const nlohmann::json gltf = glb_json(read_bytes(dir / "fit.glb"));
  ASSERT_EQ(gltf["scenes"].size(), 4u + 1u);  // the fit, three map scenes, the pose
  EXPECT_EQ(gltf["scenes"][4]["name"], "pose raised");
  const int node = gltf["scenes"][4]["nodes"][0].get<int>();
  EXPECT_EQ(gltf["nodes"][node]["name"], "pose raised");
  EXPECT_EQ(gltf["nodes"][node]["children"].size(), 2u);  // body and garment
  EXPECT_EQ(gltf["scene"], 0);                            // the neutral fit shows first
}

TEST(FitGlb, StoresColoursRangeAndGeometry) {
  test::TempDir dir("glb_layout");
  const FitView view = test::band_on_sphere(8, 2);
  const ResolvedColoring used = write_fit_glb(dir / "fit.glb", view);
  const auto bytes = read_bytes(dir / "fit.glb");
  const auto json = glb_json(bytes);
  ASSERT_EQ(json["meshes"].size(), 2u + 3u);  // body, garment, the garment of each further map
  EXPECT_EQ(json["meshes"][0]["name"], "body");
  const auto& garment = json["meshes"][1];
  EXPECT_EQ(garment["extras"]["coloring"]["field"], "stretch_max");
  EXPECT_EQ(garment["extras"]["coloring"]["colormap"], "viridis");
  EXPECT_DOUBLE_EQ(garment["extras"]["coloring"]["lo"].get<double>(), used.lo);
  EXPECT_DOUBLE_EQ(garment["extras"]["coloring"]["hi"].get<double>(), used.hi);

  // The colour of the first garment face's corners is the linear colour of its value.
  const int color_accessor = garment["primitives"][0]["attributes"]["COLOR_0"];
  const auto& accessor = json["accessors"][color_accessor];
  EXPECT_EQ(accessor["count"], 3 * view.garment.num_faces());
  const auto& buffer_view = json["bufferViews"][accessor["bufferView"].get<int>()];
  const std::size_t bin = 20 + u32_at(bytes, 12) + 8;
  const std::size_t offset = bin + buffer_view["byteOffset"].get<std::size_t>();
  const Rgb srgb = used.color(find_field(view.garment_fields, "stretch_max")->values(0, 0));
  for (int corner = 0; corner < 3; ++corner) {
    for (int k = 0; k < 3; ++k) {
      float value = 0.0f;
      std::memcpy(&value, bytes.data() + offset + 4 * static_cast<std::size_t>(3 * corner + k), 4);
      EXPECT_NEAR(value, srgb_to_linear(srgb[static_cast<std::size_t>(k)]), 1e-6);
    }
  }
}

TEST(FitGlb, WithoutBodyAndErrors) {
  test::TempDir dir("glb_errors");
  const FitView view = test::band_on_sphere(8, 2);
  GlbOptions options;
  options.include_body = false;
  write_fit_glb(dir / "garment.glb", view, options);
  EXPECT_EQ(glb_json(read_bytes(dir / "garment.glb"))["meshes"].size(), 1u + 3u);

  options.coloring.field = "no_such_field";
  EXPECT_THROW(write_fit_glb(dir / "bad.glb", view, options), InputError);
  options.coloring.field = "stretch_dir";
  EXPECT_THROW(write_fit_glb(dir / "bad.glb", view, options), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
}

/// The floats of a VEC3 float accessor of a .glb, as rows.
Points3 accessor_rows(const std::string& bytes, const nlohmann::json& gltf, int accessor) {
  const auto& a = gltf["accessors"][static_cast<std::size_t>(accessor)];
  EXPECT_EQ(a["componentType"], 5126);
  EXPECT_EQ(a["type"], "VEC3");
  const auto& view = gltf["bufferViews"][a["bufferView"].get<std::size_t>()];
  const std::size_t offset = 20 + u32_at(bytes, 12) + 8 + view["byteOffset"].get<std::size_t>();
  const auto count = a["count"].get<Eigen::Index>();
  Points3 rows(count, 3);
  for (Eigen::Index i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) {
      float value = 0.0f;
      std::memcpy(&value, bytes.data() + offset + 4 * static_cast<std::size_t>(3 * i + k), 4);
      rows(i, k) = value;
    }
  return rows;
}

TEST(FitGlb, RotationTakesTheUpDirectionOntoY) {
  for (const Vec3& up : {Vec3(0, 0, 2), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0.3, 0.4, -0.5)}) {
    const Mat3 r = glb_rotation(up);
    EXPECT_LT((r * up.normalized() - Vec3::UnitY()).norm(), 1e-12) << up.transpose();
    EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);  // a rotation, not a mirror
  }
  EXPECT_EQ(glb_rotation(Vec3::UnitY()), Mat3::Identity());
  EXPECT_EQ(glb_rotation(Vec3::Zero()), Mat3::Identity());
}

TEST(FitGlb, ABodyStandingAlongXIsTurnedYUpWithItsNormals) {
  // The test band's axis is the sphere's y; declared as standing along +x, the file
  // shows it turned so that +x is +y: positions and normals are R times the view's.
  test::TempDir dir("glb_up");
  FitView view = test::band_on_sphere(8, 2);
  view.up = Vec3::UnitX();
  view.garment_normals = view.garment.vertices.rowwise().normalized();  // the sphere's, outward
  write_fit_glb(dir / "fit.glb", view);
  const std::string bytes = read_bytes(dir / "fit.glb");
  const nlohmann::json gltf = glb_json(bytes);
  const Mat3 r = glb_rotation(view.up);
  EXPECT_EQ(gltf["asset"]["extras"]["scene_up"], nlohmann::json({1.0, 0.0, 0.0}));
  const auto& attributes = gltf["meshes"][1]["primitives"][0]["attributes"];
  const Points3 positions = accessor_rows(bytes, gltf, attributes["POSITION"].get<int>());
  const Points3 normals = accessor_rows(bytes, gltf, attributes["NORMAL"].get<int>());
  ASSERT_EQ(positions.rows(), 3 * view.garment.num_faces());
  ASSERT_EQ(normals.rows(), positions.rows());
  for (int f = 0; f < view.garment.num_faces(); ++f)
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Index row = 3 * f + corner;
      const Vec3 scene = view.garment.vertices.row(view.garment.faces(f, corner));
      EXPECT_LT((positions.row(row).transpose() - r * scene).norm(), 1e-6);
      // The band lies on the sphere: its normal is radial, away from the body.
      const Vec3 n = normals.row(row).transpose();
      EXPECT_NEAR(n.norm(), 1.0, 1e-5);
      EXPECT_GT(n.dot((r * scene).normalized()), 0.9) << "face " << f;
    }
  // The body's first vertex and its normal turned alike.
  const auto& body = gltf["meshes"][0]["primitives"][0]["attributes"];
  const Points3 body_positions = accessor_rows(bytes, gltf, body["POSITION"].get<int>());
  EXPECT_LT((body_positions.row(0).transpose() - r * view.body.vertices.row(0).transpose()).norm(),
            1e-6);
  EXPECT_LT((accessor_rows(bytes, gltf, body["NORMAL"].get<int>()).row(0).transpose() -
             r * view.body.vertices.row(0).transpose().normalized())
                .norm(),
            1e-5);  // the sphere's pole: its normal is radial
}

TEST(FitGlb, EveryMapIsAColourSetAndASceneOfItsOwn) {
  test::TempDir dir("glb_maps");
  const FitView view = test::band_on_sphere(8, 2);
  write_fit_glb(dir / "fit.glb", view);
  const std::string bytes = read_bytes(dir / "fit.glb");
  const nlohmann::json gltf = glb_json(bytes);
  const std::vector<FieldColoring> maps = standard_colorings();  // the band has all four
  const auto& garment = gltf["meshes"][1];
  const auto& attributes = garment["primitives"][0]["attributes"];
  ASSERT_EQ(garment["extras"]["color_sets"].size(), maps.size());
  ASSERT_EQ(gltf["scenes"].size(), maps.size());  // the fit, then a scene per further map
  for (std::size_t k = 0; k < maps.size(); ++k) {
    const std::string attribute = "COLOR_" + std::to_string(k);
    const auto& set = garment["extras"]["color_sets"][k];
    EXPECT_EQ(set["field"], maps[k].field);
    EXPECT_EQ(set["attribute"], attribute);
    EXPECT_EQ(gltf["asset"]["extras"]["color_sets"][k]["scene"], k);
    // The set holds the map's colours: the first face's corners.
    const FaceField* field = find_field(view.garment_fields, maps[k].field);
    ASSERT_NE(field, nullptr);
    const ResolvedColoring resolved = resolve_coloring(maps[k], *field, "test");
    const Points3 colors = accessor_rows(bytes, gltf, attributes[attribute].get<int>());
    const Rgb srgb = resolved.color(resolved.values[0]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(colors(0, c), srgb_to_linear(srgb[static_cast<std::size_t>(c)]), 1e-6)
          << attribute;
    if (k == 0) continue;
    // Scene k draws the body and the same garment geometry with this map as COLOR_0.
    const auto& scene = gltf["scenes"][k];
    EXPECT_EQ(scene["name"], "map: " + maps[k].label);
    ASSERT_EQ(scene["nodes"].size(), 2u);
    const int mesh = gltf["nodes"][scene["nodes"][1].get<std::size_t>()]["mesh"];
    const auto& map_attributes =
        gltf["meshes"][static_cast<std::size_t>(mesh)]["primitives"][0]["attributes"];
    EXPECT_EQ(map_attributes["POSITION"], attributes["POSITION"]);
    EXPECT_EQ(map_attributes["NORMAL"], attributes["NORMAL"]);
    EXPECT_EQ(map_attributes["COLOR_0"], attributes[attribute]);
    EXPECT_EQ(gltf["nodes"][scene["nodes"][0].get<std::size_t>()]["mesh"], 0);  // the body
  }
  GlbOptions one;
  one.all_maps = false;
  write_fit_glb(dir / "one.glb", view, one);
  const nlohmann::json single = glb_json(read_bytes(dir / "one.glb"));
  EXPECT_EQ(single["scenes"].size(), 1u);
  EXPECT_FALSE(single["meshes"][1]["primitives"][0]["attributes"].contains("COLOR_1"));
}

TEST(FitGlb, TheBodysUpIsItsCylinderAxisOrY) {
  const auto spec = [](const nlohmann::json& j) { return parse_body_spec(j, "", "."); };
  EXPECT_EQ(body_up_direction(spec({{"generator", "cylinder"}, {"radius", 0.05}, {"length", 0.2}})),
            Vec3::UnitZ());
  EXPECT_LT(
      (body_up_direction(spec(
           {{"generator", "cylinder"}, {"radius", 0.05}, {"length", 0.2}, {"axis", {3, 0, 4}}})) -
       Vec3(0.6, 0, 0.8))
          .norm(),
      1e-15);
  EXPECT_EQ(body_up_direction(spec({{"generator", "sphere"}, {"radius", 0.1}})), Vec3::UnitY());
  EXPECT_EQ(
      body_up_direction(spec(
          {{"mesh",
            (std::filesystem::path(TIGHTFIT_DATA_DIR) / "bodies/mh_male_regular.obj").string()}})),
      Vec3::UnitY());
}

}  // namespace tightfit::fit_glb_test
