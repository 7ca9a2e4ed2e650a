/// load_scene builds the garment on the body's surface on a thread of its own (flattening
/// the panels on the threads) while it meshes the body's volume: the scene must be the
/// same as when the stages run one after the other, and the body's errors must still come
/// before the garment's.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/scene/loader.hpp"

namespace tightfit::scene_loader_test {

const std::filesystem::path kExamples = std::filesystem::path(TIGHTFIT_SOURCE_DIR) / "examples";

/// load_scene with `threads` threads (the count is restored afterwards).
std::unique_ptr<LoadedScene> load_with_threads(const SceneSpec& spec, int threads) {
  const int before = thread_count();
  set_thread_count(threads);
  try {
    auto scene = load_scene(spec);
    set_thread_count(before);
    return scene;
  } catch (...) {
    set_thread_count(before);
    throw;
  }
}

/// The message of the InputError load_scene throws with `threads` threads.
std::string load_error(const SceneSpec& spec, int threads) {
  try {
    load_with_threads(spec, threads);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneLoader, OverlappedStagesBuildTheSceneOfTheSerialOnes) {
  const SceneSpec spec = read_scene(kExamples / "cover_sphere_three_pieces.json");
  const auto serial = load_with_threads(spec, 1);
  const auto overlapped = load_with_threads(spec, 2);
  EXPECT_EQ(serial->body.surface.vertices, overlapped->body.surface.vertices);
  EXPECT_EQ(serial->body.volume.vertices, overlapped->body.volume.vertices);
  EXPECT_EQ(serial->body.volume.tets, overlapped->body.volume.tets);
  EXPECT_EQ(serial->body.pinned, overlapped->body.pinned);
  ASSERT_GT(overlapped->body.volume.num_tets(), 0);
  EXPECT_FALSE(overlapped->body.pinned.empty());
  ASSERT_EQ(serial->garment.pattern.pieces.size(), 3u);
  EXPECT_EQ(serial->garment.rest_positions(), overlapped->garment.rest_positions());
  ASSERT_EQ(serial->garment.embedding.size(), overlapped->garment.embedding.size());
  for (size_t v = 0; v < serial->garment.embedding.size(); ++v) {
    const SurfacePoint &a = serial->garment.embedding[v], &b = overlapped->garment.embedding[v];
    EXPECT_TRUE(a.face == b.face && a.u == b.u && a.v == b.v) << "garment vertex " << v;
  }
  std::vector<std::string> stages;
  for (const auto& [stage, seconds] : overlapped->stage_seconds) {
    stages.push_back(stage);
    EXPECT_GE(seconds, 0.0) << stage;
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"body", "limit surface", "garment"}));
}

TEST(SceneLoader, TheBodysErrorComesBeforeTheGarmentsOnAnyThreadCount) {
  // The core cannot be pinned (no vertex 1 m deep in a 0.1 m sphere) and the panels
  // cannot be flattened within a 1e-9 area tolerance: the body's error is reported.
  SceneSpec spec = read_scene(kExamples / "cover_sphere_three_pieces.json");
  spec.garment.layout.area_tolerance = 1e-9;
  const std::string garment_error = load_error(spec, 2);
  EXPECT_NE(garment_error.find("too curved to flatten"), std::string::npos) << garment_error;
  EXPECT_EQ(load_error(spec, 1), garment_error);
  spec.body.volume.core.soft_tissue = 1.0;
  const std::string body_error = load_error(spec, 2);
  EXPECT_NE(body_error.find("no vertex is pinned"), std::string::npos) << body_error;
  EXPECT_EQ(load_error(spec, 1), body_error);
}

}  // namespace tightfit::scene_loader_test
