/// The shape objective's target read from a mesh coarser than the IMLS radius: the
/// signed distance must stay continuous over the surface (it jumped between the
/// vertices' tangent planes when only the mesh's vertices were used, and the optimizer's
/// line search then stalled on the shapewear example).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "report/support/fit_test_tools.hpp"
#include "support/test_meshes.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/scene/optimization_setup.hpp"

namespace tightfit::shape_target_test {

/// A path over the surface of `mesh`: from a point inside face 0, across one of its edges
/// (not at the edge's midpoint), into the neighbouring face; generic (no symmetry of
/// the icosahedron makes the nearest vertex change where values happen to agree).
std::vector<Vec3> path_across_an_edge(const TriMesh& mesh, int samples) {
  const int a = mesh.faces(0, 0), b = mesh.faces(0, 1), c = mesh.faces(0, 2);
  int other = -1;
  for (int f = 1; f < mesh.num_faces() && other < 0; ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces(f, k) == b && mesh.faces(f, (k + 1) % 3) == a)
        other = mesh.faces(f, (k + 2) % 3);
  EXPECT_GE(other, 0);
  auto v = [&](int i) -> Vec3 { return mesh.vertices.row(i).transpose(); };
  const Vec3 start = 0.6 * v(a) + 0.1 * v(b) + 0.3 * v(c);
  const Vec3 edge = 0.7 * v(a) + 0.3 * v(b);
  const Vec3 end = 0.15 * v(a) + 0.55 * v(b) + 0.3 * v(other);
  std::vector<Vec3> path;
  for (int i = 0; i <= samples; ++i) path.push_back(start + (edge - start) * i / samples);
  for (int i = 1; i <= samples; ++i) path.push_back(edge + (end - edge) * i / samples);
  return path;
}

struct Walk {
  double largest_jump = 0.0;   // m, between consecutive path points
  double largest_value = 0.0;  // m
  int fallbacks = 0;
};

Walk walk(const ImlsSurface& surface, const std::vector<Vec3>& path) {
  Walk w;
  double previous = surface.evaluate(path.front()).value;
  for (const Vec3& x : path) {
    const ImlsSurface::Evaluation e = surface.evaluate(x);
    w.largest_jump = std::max(w.largest_jump, std::abs(e.value - previous));
    w.largest_value = std::max(w.largest_value, std::abs(e.value));
    w.fallbacks += e.fallback ? 1 : 0;
    previous = e.value;
  }
  return w;
}

TEST(ShapeTarget, CoarseTargetIsSampledSoTheDistanceIsContinuous) {
  // A coarse sphere: the icosahedron split twice, radius 0.5 m (edges of about 15 cm,
  // fifteen times the IMLS radius), its vertices moved in and out by up to 1 %. The
  // path below runs over its flat facets, which lie up to 9 mm inside the smooth
  // surface the target stands for: within the radius.
  TriMesh coarse = test::unit_icosphere();
  for (int k = 0; k < coarse.num_vertices(); ++k)
    coarse.vertices.row(k) *= 0.5 * (1.0 + 0.01 * std::sin(7.0 * k + 1.0));
  const test::TempDir dir("shape_target");
  write_obj(dir / "target.obj", coarse);
  ShapeObjectiveSpec spec;
  spec.target = dir / "target.obj";
  spec.radius = 0.01;
  const ImlsSurface target = read_shape_target(spec);
  EXPECT_GT(target.points().rows(), 400);

  const std::vector<Vec3> path = path_across_an_edge(coarse, 600);
  const double step = (path[1] - path[0]).norm();  // about 0.1 mm
  const Walk sampled = walk(target, path);
  EXPECT_EQ(sampled.fallbacks, 0);
  EXPECT_LT(sampled.largest_jump, 3.0 * step);  // |∇f| is about 1: no jump
  EXPECT_LT(sampled.largest_value, 0.01);       // the facets' depth at most

  // The mesh's vertices alone (no surface sampling): far from every vertex,
  // the nearest-vertex fallback jumps (0.5 mm here) where the nearest vertex changes.
  const ImlsSurface vertices_only(coarse.vertices, vertex_normals(coarse), spec.radius);
  const Walk bare = walk(vertices_only, path);
  EXPECT_GT(bare.fallbacks, 0);
  EXPECT_GT(bare.largest_jump, 3.0 * step);
}

TEST(ShapeTarget, RefusesARadiusThatWouldNeedTooManyPoints) {
  TriMesh big = test::icosahedron();  // circumradius 1 m
  const test::TempDir dir("shape_target_big");
  write_obj(dir / "target.obj", big);
  ShapeObjectiveSpec spec;
  spec.target = dir / "target.obj";
  spec.radius = 1e-4;  // 0.05 mm spacing over about 9.6 m²
  try {
    read_shape_target(spec);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), spec.target.string());
    EXPECT_NE(std::string(e.what()).find("larger radius"), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::shape_target_test
