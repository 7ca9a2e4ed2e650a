/// Every scene in examples/ parses strictly (scene and "optimize" section), and the
/// files it names (body mesh, shape target) exist and read as meshes.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tightfit/design/optimization_spec.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/scene/spec.hpp"

namespace tightfit::example_scenes_test {

namespace fs = std::filesystem;

TEST(ExampleScenes, EveryExampleParsesAndItsFilesRead) {
  const fs::path dir = fs::path(TIGHTFIT_SOURCE_DIR) / "examples";
  int scenes = 0, optimizing = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ++scenes;
    SceneSpec scene;
    ASSERT_NO_THROW(scene = read_scene(entry.path()));
    if (scene.body.source == BodySource::kMesh) {
      EXPECT_TRUE(fs::exists(scene.body.mesh.path)) << scene.body.mesh.path;
    }
    if (scene.optimize.is_null()) continue;
    ++optimizing;
    OptimizationSpec spec;
    ASSERT_NO_THROW(spec = parse_optimization_spec(scene.optimize, entry.path().string(),
                                                   "/optimize", scene.base_dir));
    if (spec.shape) {
      const TriMesh target = read_tri_mesh(spec.shape->target);
      EXPECT_GT(target.num_faces(), 0) << spec.shape->target;
    }
  }
  EXPECT_GE(scenes, 1);
  EXPECT_GE(optimizing, 1);
}

}  // namespace tightfit::example_scenes_test
