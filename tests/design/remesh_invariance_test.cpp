/// Remeshing does not change the objective: a fit, remeshed finer and coarser and brought
/// back to equilibrium, gives every design term within 1 % of its value on the original
/// mesh when the terms' weights refer to the original mesh (objectives/resolution.hpp),
/// as the optimizer rebuilds them after a remeshing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "adjoint_test_scene.hpp"
#include "tightfit/design/pattern_remesh.hpp"
#include "tightfit/objectives/directional_stretch_objective.hpp"
#include "tightfit/objectives/pinned_traction_regularizer.hpp"
#include "tightfit/objectives/pressure_objective.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/regularizer_corner_angle.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/regularizer_smoothness.hpp"
#include "tightfit/objectives/resolution.hpp"
#include "tightfit/objectives/seam_traction_objective.hpp"
#include "tightfit/objectives/shape_objective.hpp"
#include "tightfit/objectives/stretch_objective.hpp"

namespace tightfit::remesh_invariance_test {

using test::make_sleeve_scene;
using test::SleeveSceneOptions;

/// A cylinder of radius `radius` about the z axis as an IMLS target (points and outward
/// normals on a grid).
ImlsSurface cylinder_target(double radius) {
  const int rings = 30, around = 48;
  Points3 p(rings * around, 3), n(rings * around, 3);
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < around; ++k) {
      const double a = 2.0 * std::numbers::pi * k / around, z = -0.06 + 0.12 * i / (rings - 1);
      p.row(i * around + k) << radius * std::cos(a), radius * std::sin(a), z;
      n.row(i * around + k) << std::cos(a), std::sin(a), 0.0;
    }
  return ImlsSurface(p, n, 0.01);
}

/// The fit's terms (of the garment positions and the equilibrium), built on the
/// simulation's current garment with weights that refer to `reference`. The sliding
/// objective is weighted alike (sliding_vertex_weights) but not among them: the excess
/// force of each vertex in a pose depends on the mesh's regularity itself (on this
/// sleeve in a cone-shaped pose: 1.1 on a jittered mesh, 0.054 on a regular one, 0.10 on
/// the remeshed one at the same edge length), far beyond any weighting.
std::vector<std::shared_ptr<const DesignTerm>> fit_terms(const GarmentSimulation& sim,
                                                         const ResolutionReference& reference) {
  const Garment& g = sim.garment();
  const ClothMaterial& fabric = sim.materials().fabric;
  return {
      std::make_shared<StretchObjective>(g, StretchBounds{1.0, 1.02}),
      std::make_shared<DirectionalStretchObjective>(g, FabricDirection::kAcrossGrain,
                                                    StretchBounds{1.0, 1.02}),
      std::make_shared<PressureObjective>(g, fabric, 500.0, 500.0),
      std::make_shared<SeamTractionObjective>(g, fabric),
      std::make_shared<ShapeObjective>(cylinder_target(0.055), g.num_garment_vertices(),
                                       std::vector<int>{}, shape_vertex_weights(g, reference)),
      std::make_shared<PinnedTractionRegularizer>(g, sim.materials(), sim.surface(), reference),
  };
}

/// The pattern's regularizers (of the rest shape only), built on the current garment.
/// Boundary spacing is not among them: it measures the spacing of the boundary vertices
/// themselves, which a remeshing makes even (0 on any evenly spaced mesh).
std::vector<std::shared_ptr<const DesignTerm>> pattern_terms(const GarmentSimulation& sim,
                                                             const ResolutionReference& reference) {
  const Garment& g = sim.garment();
  return {
      std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(g, reference)),
      std::make_shared<BoundarySmoothnessRegularizer>(g),
      std::make_shared<CompactnessRegularizer>(g, CompactnessOptions{0.5, 1}, reference),
      std::make_shared<CornerAngleRegularizer>(g),
  };
}

/// The rest positions moved by one smooth map of the piece plane, the same for every mesh
/// of the piece: the seam side at x = `width` bulges out by up to 4 mm (the seam's sides
/// differ, its outline curves, its corners turn), the rest of the piece follows.
Points2 bulged(const Points2& rest, double width, double height) {
  Points2 out = rest;
  for (Eigen::Index i = 0; i < rest.rows(); ++i)
    out(i, 0) += 0.004 * (rest(i, 0) / width) * std::sin(std::numbers::pi * rest(i, 1) / height);
  return out;
}

std::vector<double> values(const GarmentSimulation& sim,
                           const std::vector<std::shared_ptr<const DesignTerm>>& terms,
                           const Points2& rest) {
  const Points3& positions = sim.garment_positions();
  const VecX x = Eigen::Map<const VecX>(positions.data(), positions.size());
  const DesignEmbedding embedding{sim.problem().state().garment, sim.body_positions()};
  const DesignState state{x, rest, &embedding};
  std::vector<double> out;
  for (const auto& term : terms) out.push_back(term->value(state));
  return out;
}

/// The values of the fit's terms at the equilibrium and of the pattern's at the bulged
/// rest shape, with their names.
std::pair<std::vector<std::string>, std::vector<double>> all_values(
    const GarmentSimulation& sim, const ResolutionReference& reference) {
  const PatternPiece& piece = sim.garment().pattern.pieces[0];
  const double width = piece.rest.col(0).maxCoeff(), height = piece.rest.col(1).maxCoeff();
  const auto fit = fit_terms(sim, reference);
  const auto pattern = pattern_terms(sim, reference);
  std::vector<double> v = values(sim, fit, sim.garment().rest_positions());
  const std::vector<double> p =
      values(sim, pattern, bulged(sim.garment().rest_positions(), width, height));
  v.insert(v.end(), p.begin(), p.end());
  std::vector<std::string> names;
  for (const auto& t : fit) names.push_back(t->name());
  for (const auto& t : pattern) names.push_back(t->name());
  return {names, v};
}

TEST(RemeshInvariance, EveryTermIsWithinOnePercentOnAFinerAndACoarserMeshOfTheSameFit) {
  // Finer, and at the same edge length (a new triangulation, as the optimizer's
  // remeshing makes). Coarser meshes change the fit itself: at 1.3 times the edge,
  // stretch and pressure fall by 2 % (the chords of the coarser triangles).
  for (const double factor : {0.75, 1.0}) {
    SleeveSceneOptions so;
    so.jitter = 0.0;
    so.hoop_scale = 0.8;     // taut around: pressure, traction and stretch penalties
    so.edge_length = 0.008;  // fine enough that the fit itself hardly depends on the mesh
    auto scene = make_sleeve_scene(so);
    GarmentSimulation& sim = *scene->sim;
    ASSERT_TRUE(sim.solve().converged);
    const ResolutionReference reference = resolution_of(sim.garment());
    const auto [names, before] = all_values(sim, reference);

    const Garment old = sim.garment();
    const double h = factor * mean_edge_length(old.pattern.pieces[0]);
    const PatternRemeshResult r = remesh_garment(
        old, sim.problem().state(), sim.garment_positions(), sim.surface(), {0}, {h}, 10);
    sim.replace_garment(r.garment, r.state);
    ASSERT_TRUE(sim.solve().converged);
    const std::vector<double> after = all_values(sim, reference).second;
    std::printf("  edge x%.1f: %d -> %d garment vertices\n", factor, old.num_garment_vertices(),
                sim.garment().num_garment_vertices());
    for (size_t k = 0; k < before.size(); ++k) {
      const std::string& name = names[k];
      std::printf("    %-20s %.6e -> %.6e  (%+.2f %%)\n", name.c_str(), before[k], after[k],
                  100.0 * (after[k] / before[k] - 1.0));
      EXPECT_GT(before[k], 0.0) << name << ": the scene must exercise every term";
      EXPECT_NEAR(after[k], before[k], 0.01 * before[k]) << name << ", edge x" << factor;
    }
  }
}

}  // namespace tightfit::remesh_invariance_test
