#include "tightfit/io/fit_glb.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/fit_test_tools.hpp"
#include "io/fit_test_view.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

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

  const auto result =
      test::run_command("node " + test::shell_quote(test::source_path("tests/io/fit_glb_validate.mjs")) +
                            " " + test::shell_quote(dir / "fit.glb"),
                        dir / "validator.log");
  ASSERT_EQ(result.exit_code, 0) << "gltf-validator (node, report/node_modules; see "
                                 << "scripts/install-deps.sh) reported errors or could not run:\n"
                                 << result.output;
  const auto report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["numErrors"], 0) << result.output;
  EXPECT_EQ(report["numWarnings"], 0) << result.output;
  EXPECT_EQ(report["info"]["drawCallCount"], 2) << result.output;
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
  const auto result =
      test::run_command("node " + test::shell_quote(test::source_path("tests/io/fit_glb_validate.mjs")) +
                            " " + test::shell_quote(dir / "fit.glb"),
                        dir / "validator.log");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["numErrors"], 0) << result.output;
  EXPECT_EQ(report["numWarnings"], 0) << result.output;
  const nlohmann::json gltf = glb_json(read_bytes(dir / "fit.glb"));
  ASSERT_EQ(gltf["scenes"].size(), 2u);
  EXPECT_EQ(gltf["scenes"][1]["name"], "pose raised");
  const int node = gltf["scenes"][1]["nodes"][0].get<int>();
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
  ASSERT_EQ(json["meshes"].size(), 2u);
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
  EXPECT_EQ(glb_json(read_bytes(dir / "garment.glb"))["meshes"].size(), 1u);

  options.coloring.field = "no_such_field";
  EXPECT_THROW(write_fit_glb(dir / "bad.glb", view, options), InputError);
  options.coloring.field = "stretch_dir";
  EXPECT_THROW(write_fit_glb(dir / "bad.glb", view, options), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
}

}  // namespace
}  // namespace tightfit
