#include "tightfit/report/fit_view.hpp"

#include <gtest/gtest.h>

#include "report/support/fit_test_view.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::fit_view_test {

TEST(FitView, BandOnSphereIsValid) {
  const FitView view = test::band_on_sphere(8, 2);
  EXPECT_NO_THROW(validate_fit_view(view, "test"));
  EXPECT_EQ(view.garment.num_faces(), 2 * 2 * 8 * 2);
}

TEST(FitView, DefaultMappingConcatenatesPieces) {
  const FitView view = test::band_on_sphere(4, 1);
  const auto map = resolved_piece_faces(view);
  ASSERT_EQ(map.size(), 2u);
  ASSERT_EQ(map[0].size(), 8u);
  EXPECT_EQ(map[0].front(), 0);
  EXPECT_EQ(map[1].front(), 8);
  EXPECT_EQ(map[1].back(), 15);
  EXPECT_EQ(map[0].back(), 7);  // face 7 on piece 0, face 8 on piece 1
}

TEST(FitView, ExplicitMappingIsUsed) {
  FitView view = test::band_on_sphere(4, 1);
  std::vector<int> front, back;
  for (int f = 0; f < 16; ++f) (f % 2 == 0 ? front : back).push_back(f);
  view.piece_faces = {front, back};
  EXPECT_NO_THROW(validate_fit_view(view, "test"));
  const auto map = resolved_piece_faces(view);
  ASSERT_EQ(map.size(), 2u);
  EXPECT_EQ(map[0], front);
  EXPECT_EQ(map[1], back);
}

void expect_input_error(const FitView& view, const std::string& fragment) {
  try {
    validate_fit_view(view, "out.glb");
    FAIL() << "expected InputError containing '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out.glb: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(FitView, RejectsBadInput) {
  const FitView good = test::band_on_sphere(4, 1);
  {
    FitView v = good;
    v.garment_fields[0].values.conservativeResize(3, 1);
    expect_input_error(v, "'stretch_max' has 3x1 values for 16 faces");
  }
  {
    FitView v = good;
    v.garment_fields[1].name = "bad name";
    expect_input_error(v, "field name 'bad name'");
  }
  {
    FitView v = good;
    v.garment_fields[1].name = v.garment_fields[0].name;
    expect_input_error(v, "appears twice");
  }
  {
    FitView v = good;
    v.garment.faces(2, 1) = 1000;
    expect_input_error(v, "garment has a face index outside");
  }
  {
    FitView v = good;
    v.pattern.pieces.pop_back();
    expect_input_error(v, "the pattern has 8 triangles but the garment has 16 faces");
  }
  {
    FitView v = good;
    std::vector<int> all(8, 0);
    for (int i = 0; i < 8; ++i) all[static_cast<std::size_t>(i)] = i;
    v.piece_faces = {all, all};
    expect_input_error(v, "twice");
  }
  {
    FitView v = good;
    v.history = nlohmann::json::object();
    expect_input_error(v, "history must be a JSON array");
  }
  {
    FitView v = good;
    v.summary = nlohmann::json::array();
    expect_input_error(v, "summary must be a JSON object");
  }
  {
    FitView v = good;
    v.initial_outlines = {Points2::Zero(4, 2)};  // one outline, two pieces
    expect_input_error(v, "1 initial outlines for 2 pieces");
    v.initial_outlines = {Points2::Zero(4, 2), Points2::Constant(3, 2, std::nan(""))};
    expect_input_error(v, "is not a polygon of finite points");
    v.initial_outlines = {Points2::Zero(4, 2), Points2()};  // no outline for the second
    EXPECT_NO_THROW(validate_fit_view(v, "report.html"));
  }
  {
    FitView v = good;
    v.garment_normals = Points3::Zero(v.garment.vertices.rows() - 1, 3);
    expect_input_error(v, "one per garment vertex");
    v.garment_normals = Points3::Zero(v.garment.vertices.rows(), 3);
    v.pinned_vertices = {static_cast<int>(v.garment.vertices.rows())};
    expect_input_error(v, "is not a garment vertex");
  }
  {
    FitView v = good;
    v.body.vertices(0, 0) = std::nan("");
    expect_input_error(v, "body has non-finite vertex positions");
  }
}

TEST(FitView, PressureInMmHg) {
  FaceField pa{"pressure_pa", "Pa", MatX::Constant(2, 1, kPascalPerMmHg * 20.0)};
  const FaceField mmhg = pressure_mmhg_field(pa);
  EXPECT_EQ(mmhg.name, "pressure_mmhg");
  EXPECT_EQ(mmhg.unit, "mmHg");
  EXPECT_NEAR(mmhg.values(1, 0), 20.0, 1e-12);
  EXPECT_NE(find_field({pa, mmhg}, "pressure_mmhg"), nullptr);
  EXPECT_EQ(find_field({pa}, "pressure_mmhg"), nullptr);
}

}  // namespace tightfit::fit_view_test
