// The sliding objective (Eq. 37-38): its partial derivatives against finite differences,
// and the whole simulate-then-evaluate pipeline's adjoint gradient.
#include "tightfit/objectives/sliding_objective.hpp"
#include "tightfit/objectives/all_poses_term.hpp"
#include "tightfit/objectives/pinned_traction_regularizer.hpp"
#include "tightfit/objectives/stretch_objective.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <functional>
#include <random>

#include "design/adjoint_test_scene.hpp"
#include "tightfit/design/adjoint_check.hpp"
#include "tightfit/design/adjoint_gradient.hpp"
#include "tightfit/design/optimization_problem.hpp"

namespace tightfit::sliding_objective_test {

/// A twist-and-bend "pose" of the sleeve's capsule: body vertex p turns rigidly by an
/// angle that grows smoothly along the axis (twist about z up to `twist` degrees, bend
/// about x up to `bend` degrees), as dual-quaternion skinning of a two-bone chain would.
PoseMotions twist_pose(const Body& body, double twist, double bend) {
  PoseMotions pose{"twist", {}};
  for (int k = 0; k < body.num_vertices(); ++k) {
    const Vec3 p = body.volume.vertices.row(k);
    const double t = std::clamp((p.z() + 0.06) / 0.12, 0.0, 1.0);
    const double s = t * t * (3.0 - 2.0 * t);
    const Mat3 R = (Eigen::AngleAxisd(s * bend * EIGEN_PI / 180.0, Vec3::UnitX()) *
                    Eigen::AngleAxisd(s * twist * EIGEN_PI / 180.0, Vec3::UnitZ()))
                       .toRotationMatrix();
    const Vec3 pivot(0.0, 0.0, -0.06);
    pose.motions.push_back({R, pivot - R * pivot});
  }
  return pose;
}

struct SlidingScene {
  std::unique_ptr<test::SleeveScene> scene;
  std::shared_ptr<SlidingObjective> term;
};

SlidingScene sliding_scene(double friction) {
  test::SleeveSceneOptions o;
  o.soft_body = true;
  SlidingScene s{test::make_sleeve_scene(o), nullptr};
  GarmentSimulation& sim = *s.scene->sim;
  sim.solve();
  std::vector<PoseMotions> poses{twist_pose(s.scene->body, 25.0, 10.0),
                                 twist_pose(s.scene->body, -15.0, 20.0)};
  poses[1].name = "bend";
  s.term = std::make_shared<SlidingObjective>(sim.garment(), sim.materials(), *s.scene->surface,
                                              s.scene->body.num_vertices(), std::move(poses),
                                              friction, sliding_vertex_weights(sim.garment(), {}));
  return s;
}

double central(const std::function<double(double)>& f, double h) {
  return (8.0 * (f(h) - f(-h)) - (f(2 * h) - f(-2 * h))) / (12.0 * h);
}

/// The adjoint design gradient of `term` alone against finite differences of the whole
/// pipeline along two random directions from a perturbed start (seed `seed`); each
/// check's relative error must be below 1e-6. Returns the checks.
std::vector<DirectionalCheck> pipeline_checks(GarmentSimulation& sim,
                                              std::shared_ptr<const DesignTerm> term, unsigned seed,
                                              const char* label) {
  auto objective = std::make_shared<DesignTermSum>();
  objective->add(std::move(term), 1.0);
  DesignProblem problem(sim, objective);
  GradientCheckOptions options;
  options.directions = 2;
  const VecX p =
      problem.initial_parameters() +
      0.1 * problem.mean_boundary_edge() * random_design_direction(problem.num_parameters(), seed);
  const std::vector<DirectionalCheck> checks = check_design_gradient(problem, p, options);
  for (const DirectionalCheck& c : checks) {
    EXPECT_LT(c.relative_error, 1e-6)
        << label << ": adjoint " << c.adjoint << " FD " << c.finite_difference;
    std::printf("%s: adjoint %.9e, FD %.9e, relative error %.2e\n", label, c.adjoint,
                c.finite_difference, c.relative_error);
  }
  return checks;
}

TEST(SlidingObjective, PosesPullTheClothAcrossTheBodyAndFrictionHoldsPartOfIt) {
  SlidingScene s = sliding_scene(0.3);
  const SimulationDesignState ds(*s.scene->sim);
  const double with_friction = s.term->value(ds.view());
  EXPECT_GT(with_friction, 0.0);
  const SlidingForces f = s.term->pose_view(ds.view(), 0).forces;
  EXPECT_GT(f.normal.maxCoeff(), 0.0);  // the sleeve presses on the body
  for (int v : s.scene->sim->garment().topology->pinned) EXPECT_EQ(f.excess[v], 0.0);
  // More friction holds more; none at all lets every tangential force slide.
  const SlidingScene frictionless = sliding_scene(0.0);
  EXPECT_GT(frictionless.term->value(ds.view()), with_friction);
  const SlidingScene sticky = sliding_scene(5.0);
  EXPECT_LT(sticky.term->value(ds.view()), with_friction);
  // The neutral pose (identity motions) leaves only the equilibrium's residual forces.
  std::vector<PoseMotions> rest{{"rest", std::vector<PointMotion>(s.scene->body.num_vertices())}};
  const SlidingObjective neutral(s.scene->sim->garment(), s.scene->sim->materials(),
                                 *s.scene->surface, s.scene->body.num_vertices(), rest, 0.3);
  EXPECT_LT(neutral.value(ds.view()), 1e-12 * with_friction);
  EXPECT_THROW(SlidingObjective(s.scene->sim->garment(), s.scene->sim->materials(),
                                *s.scene->surface, s.scene->body.num_vertices(), rest, -0.1),
               InputError);
}

TEST(SlidingObjective, PartialDerivativesMatchFiniteDifferences) {
  SlidingScene s = sliding_scene(0.3);
  const SimulationDesignState ds(*s.scene->sim);
  const DesignState state = ds.view();
  ASSERT_GT(s.term->value(state), 0.0);
  VecX d_x = VecX::Zero(ds.x.size()), d_rest = VecX::Zero(2 * ds.rest.rows());
  VecX d_s = VecX::Zero(2 * static_cast<Eigen::Index>(ds.garment.size())),
       d_y = VecX::Zero(ds.body.size());
  s.term->add_gradient(state, d_x, d_rest);
  s.term->add_embedding_gradient(state, d_s, d_y);
  EXPECT_EQ(d_x.norm(), 0.0);  // T does not look at the neutral positions themselves

  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  auto direction = [&](Eigen::Index n) {
    VecX d(n);
    for (Eigen::Index i = 0; i < n; ++i) d[i] = normal(rng);
    return d;
  };
  // Rest positions.
  const VecX dr = direction(d_rest.size());
  auto T_rest = [&](double t) {
    Points2 rest = ds.rest + t * Eigen::Map<const Points2>(dr.data(), ds.rest.rows(), 2);
    return s.term->value(DesignState{ds.x, rest, &ds.embedding});
  };
  // Small steps: the hinge T = max(f_t − f_c, 0) is only C¹, and some vertices sit near it.
  const double fd_rest = central(T_rest, 1e-7);
  EXPECT_NEAR(d_rest.dot(dr), fd_rest, 1e-6 * std::abs(fd_rest));
  // Body positions.
  const VecX dy = direction(d_y.size());
  auto T_body = [&](double t) {
    const Points3 body = ds.body + t * Eigen::Map<const Points3>(dy.data(), ds.body.rows(), 3);
    const DesignEmbedding e{ds.garment, body};
    return s.term->value(DesignState{ds.x, ds.rest, &e});
  };
  const double fd_body = central(T_body, 1e-8);
  EXPECT_NEAR(d_y.dot(dy), fd_body, 1e-6 * std::abs(fd_body));
  // Surface coordinates: move free garment vertices that lie well inside their face.
  VecX du = VecX::Zero(d_s.size());
  for (std::size_t j = 0; j < ds.garment.size(); ++j) {
    const SurfacePoint& p = ds.garment[j];
    if (p.u > 0.05 && p.v > 0.05 && p.u + p.v < 0.95)
      du.segment<2>(2 * static_cast<Eigen::Index>(j)) = direction(2);
  }
  ASSERT_GT(du.norm(), 0.0);
  auto T_surface = [&](double t) {
    std::vector<SurfacePoint> garment = ds.garment;
    for (std::size_t j = 0; j < garment.size(); ++j) {
      garment[j].u += t * du[2 * static_cast<Eigen::Index>(j)];
      garment[j].v += t * du[2 * static_cast<Eigen::Index>(j) + 1];
    }
    const DesignEmbedding e{garment, ds.body};
    return s.term->value(DesignState{ds.x, ds.rest, &e});
  };
  const double fd_surface = central(T_surface, 1e-7);
  EXPECT_NEAR(d_s.dot(du), fd_surface, 1e-6 * std::abs(fd_surface));
  std::printf("sliding partials: rest %.6e vs FD %.6e, body %.6e vs %.6e, surface %.6e vs %.6e\n",
              d_rest.dot(dr), fd_rest, d_y.dot(dy), fd_body, d_s.dot(du), fd_surface);
}

TEST(SlidingObjective, AdjointGradientOfTheWholePipelineMatchesFiniteDifferences) {
  SlidingScene s = sliding_scene(0.3);
  for (const DirectionalCheck& c : pipeline_checks(*s.scene->sim, s.term, 3, "sliding pipeline")) {
    EXPECT_NE(c.adjoint, 0.0);
    EXPECT_EQ(c.hessian_shift, 0.0);
  }
}

TEST(AllPosesTerm, StretchInEveryPoseHasTheAdjointGradientOfTheWholePipeline) {
  SlidingScene s = sliding_scene(0.3);
  GarmentSimulation& sim = *s.scene->sim;
  StretchBounds bounds;
  bounds.min_stretch = 1.0;
  bounds.max_stretch = 1.05;
  auto stretch = std::make_shared<StretchObjective>(sim.garment(), bounds);
  auto all = std::make_shared<AllPosesTerm>(stretch, *s.scene->surface, s.term->poses());
  const SimulationDesignState ds(sim);
  // Neutral value plus one value per pose; the twisted poses stretch the sleeve more.
  const double neutral = stretch->value(ds.view());
  EXPECT_NEAR(all->value(ds.view()),
              neutral + all->pose_value(ds.view(), 0) + all->pose_value(ds.view(), 1), 1e-15);
  EXPECT_GT(all->pose_value(ds.view(), 0), neutral);
  EXPECT_EQ(all->name(), "stretch (all poses)");
  for (const DirectionalCheck& c : pipeline_checks(sim, all, 5, "stretch in all poses"))
    EXPECT_NE(c.adjoint, 0.0);
}

TEST(PinnedTractionRegularizer, PartialsAndThePipelineMatchFiniteDifferences) {
  SlidingScene s = sliding_scene(0.3);
  GarmentSimulation& sim = *s.scene->sim;
  const auto term = std::make_shared<PinnedTractionRegularizer>(sim.garment(), sim.materials(),
                                                                *s.scene->surface);
  const SimulationDesignState ds(sim);
  ASSERT_GT(term->value(ds.view()), 0.0);  // the axially short sleeve pulls on its cuffs
  VecX d_x = VecX::Zero(ds.x.size()), d_rest = VecX::Zero(2 * ds.rest.rows());
  VecX d_s = VecX::Zero(2 * static_cast<Eigen::Index>(ds.garment.size())),
       d_y = VecX::Zero(ds.body.size());
  term->add_gradient(ds.view(), d_x, d_rest);
  term->add_embedding_gradient(ds.view(), d_s, d_y);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  auto direction = [&](Eigen::Index n) {
    VecX d(n);
    for (Eigen::Index i = 0; i < n; ++i) d[i] = normal(rng);
    return d;
  };
  const VecX dx = direction(d_x.size()), dr = direction(d_rest.size()), dy = direction(d_y.size());
  const double fd_x = central(
      [&](double t) {
        const VecX x = ds.x + t * dx;
        return term->value(DesignState{x, ds.rest, &ds.embedding});
      },
      1e-7);
  const double fd_rest = central(
      [&](double t) {
        const Points2 rest = ds.rest + t * Eigen::Map<const Points2>(dr.data(), ds.rest.rows(), 2);
        return term->value(DesignState{ds.x, rest, &ds.embedding});
      },
      1e-7);
  const double fd_body = central(
      [&](double t) {
        const Points3 body = ds.body + t * Eigen::Map<const Points3>(dy.data(), ds.body.rows(), 3);
        const DesignEmbedding e{ds.garment, body};
        return term->value(DesignState{ds.x, ds.rest, &e});
      },
      1e-7);
  EXPECT_NEAR(d_x.dot(dx), fd_x, 1e-6 * std::abs(fd_x));
  EXPECT_NEAR(d_rest.dot(dr), fd_rest, 1e-6 * std::abs(fd_rest));
  EXPECT_NEAR(d_y.dot(dy), fd_body, 1e-6 * std::abs(fd_body) + 1e-12);
  pipeline_checks(sim, term, 7, "pinned traction pipeline");
}

}  // namespace tightfit::sliding_objective_test
