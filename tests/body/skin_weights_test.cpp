#include "tightfit/body/skin_weights.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tightfit/common/error.hpp"

namespace tightfit::skin_weights_test {

const std::filesystem::path kData = TIGHTFIT_DATA_DIR;

TEST(SkinWeights, MakeHumanWeightsOnTheRegularBody) {
  const SkinWeights rig =
      read_skin_weights(kData / "bodies/mh_male_regular.obj", kData / "rig/default_weights.mhw");
  EXPECT_EQ(rig.vertices.rows(), 13380);
  EXPECT_GT(rig.bones.size(), 100u);
  ASSERT_TRUE(rig.bones.count("upperleg01.L"));
  for (const auto& [bone, entries] : rig.bones)
    for (const auto& [v, w] : entries) {
      ASSERT_LT(v, rig.vertices.rows()) << bone;  // helper geometry skipped
      ASSERT_GT(w, 0.0) << bone;
    }
  // Every vertex has weights, normalized to sum to one.
  std::vector<std::string> all;
  for (const auto& [bone, entries] : rig.bones) all.push_back(bone);
  const VecX total = rig.summed(all, "test");
  EXPECT_NEAR(total.minCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(total.maxCoeff(), 1.0, 1e-12);
  // The left thigh bones carry the left thigh (x > 0 in this body's frame), not the right.
  const VecX thigh = rig.summed({"upperleg01.L", "upperleg02.L"}, "test");
  double left = 0.0, right = 0.0;
  for (Eigen::Index v = 0; v < thigh.size(); ++v)
    (rig.vertices(v, 0) > 0 ? left : right) += thigh[v];
  EXPECT_GT(left, 100.0);
  EXPECT_LT(right, 1e-2 * left);  // a little across the midline at the crotch
  try {
    rig.summed({"tail"}, "pressure region \"x\"");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no bone \"tail\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pressure region \"x\""), std::string::npos);
  }
}

TEST(SkinWeights, MalformedFilesAreInputErrorsNamingThePath) {
  const auto dir = std::filesystem::temp_directory_path() / "tightfit_skin_weights_test";
  std::filesystem::create_directories(dir);
  auto error_of = [&](const std::string& text) -> std::string {
    std::ofstream(dir / "w.mhw") << text;
    try {
      read_skin_weights(kData / "bodies/mh_head_neutral.obj", dir / "w.mhw");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of(R"({"name": "x"})").find("/weights"), std::string::npos);
  EXPECT_NE(error_of(R"({"weights": {"a": [[1, -0.5]]}})").find("/weights/a/0"), std::string::npos);
  EXPECT_NE(error_of(R"({"weights": {"a": [[-1, 0.5]]}})").find("negative vertex"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"weights": {"a": [1, 0.5]}})").find("[vertex, weight]"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"weights": {"a": [[1, 0.5], [99999999, 1]]}})"), "");
  std::filesystem::remove_all(dir);
}

}  // namespace tightfit::skin_weights_test
