#include "tightfit/solve/newton_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tightfit/common/error.hpp"

namespace tightfit::newton_solver_test {

/// A flat-space problem defined by callbacks over a vector state q.
class VectorProblem : public NewtonProblem {
 public:
  explicit VectorProblem(VecX q0) : base_(std::move(q0)), q_(base_) {}
  Eigen::Index num_dofs() const override { return q_.size(); }
  bool set_step(const VecX& dq, double alpha) override {
    q_ = base_ + alpha * dq;
    return true;
  }
  void commit() override { base_ = q_; }
  const VecX& q() const { return q_; }

 protected:
  VecX base_;
  VecX q_;
};

/// Nonlinear chain: U = Σ_i [½ d_i² + ¼ d_i⁴] + Σ_i ¼ q_i⁴ − b·q, d_i = q_{i+1} − q_i.
/// Strictly convex, unique minimizer; sparse tridiagonal Hessian.
class ChainProblem : public VectorProblem {
 public:
  explicit ChainProblem(int n) : VectorProblem(VecX::Zero(n)), b_(VecX::LinSpaced(n, 1.0, 3.0)) {}
  /// Changes the load (a design change of the problem); the state is kept.
  void scale_load(double factor) { b_ *= factor; }
  double energy() override {
    double e = 0.25 * q_.array().pow(4).sum() - b_.dot(q_);
    for (Eigen::Index i = 0; i + 1 < q_.size(); ++i) {
      const double d = q_[i + 1] - q_[i];
      e += 0.5 * d * d + 0.25 * d * d * d * d;
    }
    return e;
  }
  VecX gradient() override {
    VecX g = q_.array().pow(3).matrix() - b_;
    for (Eigen::Index i = 0; i + 1 < q_.size(); ++i) {
      const double d = q_[i + 1] - q_[i];
      const double f = d + d * d * d;
      g[i] -= f;
      g[i + 1] += f;
    }
    return g;
  }
  SparseMatrix hessian() override {
    std::vector<Triplet> t;
    for (Eigen::Index i = 0; i < q_.size(); ++i) t.emplace_back(i, i, 3.0 * q_[i] * q_[i]);
    for (Eigen::Index i = 0; i + 1 < q_.size(); ++i) {
      const double d = q_[i + 1] - q_[i];
      const double k = 1.0 + 3.0 * d * d;
      const int a = static_cast<int>(i), c = static_cast<int>(i + 1);
      t.emplace_back(a, a, k);
      t.emplace_back(c, c, k);
      t.emplace_back(a, c, -k);
      t.emplace_back(c, a, -k);
    }
    SparseMatrix H(q_.size(), q_.size());
    H.setFromTriplets(t.begin(), t.end());
    return H;
  }

 private:
  VecX b_;
};

TEST(NewtonSolver, ConvergesQuadraticallyOnASparseConvexProblem) {
  ChainProblem problem(200);
  NewtonSolver solver;
  const NewtonReport r = solver.solve(problem);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.final_force_norm, r.tolerance);
  // Quadratic convergence: once in the basin, r_{k+1} <= C r_k^2.
  int quadratic_steps = 0;
  for (size_t k = 1; k + 1 < r.history.size(); ++k) {
    const double rk = r.history[k].force_norm, rk1 = r.history[k + 1].force_norm;
    if (rk < 1e-1 && rk1 > 1e-13) {
      EXPECT_LT(rk1, 10.0 * rk * rk) << "iteration " << k;
      ++quadratic_steps;
    }
  }
  EXPECT_GE(quadratic_steps, 1);
  EXPECT_GT(r.factor_nonzeros, 0);
}

/// Solves `problem` and factorizes its Hessian at the equilibrium into `held` (the
/// factorization a design step starts from).
void solve_and_factorize(ChainProblem& problem, SparseCholesky& held) {
  NewtonSolver first;
  ASSERT_TRUE(first.solve(problem).converged);
  ASSERT_TRUE(held.factorize(problem.hessian()));
}

TEST(NewtonSolver, ChordStepsFromAHeldFactorizationNeedNoNewFactorization) {
  ChainProblem problem(200);
  SparseCholesky held;  // the Hessian at the old equilibrium
  solve_and_factorize(problem, held);
  const VecX old_solution = problem.q();

  problem.scale_load(1.001);  // a small design step
  NewtonSolver chord_solver;
  const NewtonReport r = chord_solver.solve(problem, {&held, false});
  ASSERT_TRUE(r.converged);
  EXPECT_GE(r.chord_steps, 1);
  EXPECT_EQ(r.factorizations, 0) << "the chord steps should have converged on their own";
  for (const NewtonIteration& it : r.history) EXPECT_TRUE(it.chord);
  const VecX chord_solution = problem.q();

  // Same equilibrium as plain Newton from the old solution (to the tolerance).
  ChainProblem reference(200);
  reference.set_step(old_solution, 1.0);
  reference.commit();
  reference.scale_load(1.001);
  NewtonSolver plain;
  const NewtonReport p = plain.solve(reference);
  ASSERT_TRUE(p.converged);
  EXPECT_GE(p.factorizations, 1);
  EXPECT_LT((chord_solution - reference.q()).norm(), 1e-8 * reference.q().norm());
}

TEST(NewtonSolver, SlowChordStepsHandOverToNewton) {
  ChainProblem problem(100);
  SparseCholesky held;
  solve_and_factorize(problem, held);
  problem.scale_load(3.0);  // far: the old Hessian is a poor model
  NewtonOptions o;
  o.max_chord_steps = 10;
  NewtonSolver solver(o);
  const NewtonReport r = solver.solve(problem, {&held, false});
  ASSERT_TRUE(r.converged);
  EXPECT_GE(r.factorizations, 1);
  EXPECT_LT(r.chord_steps, 10);
  // Once Newton took over, every later step is a Newton step.
  bool newton_seen = false;
  for (const NewtonIteration& it : r.history) {
    if (!it.chord) newton_seen = true;
    if (newton_seen) {
      EXPECT_FALSE(it.chord);
    }
  }
}

// A warm start asked to stop after a poor predictor: far from the held factorization's
// equilibrium it stops after that one step (no exception, no factorization) with the
// state the step reached; near it, the same request changes nothing.
TEST(NewtonSolver, StopsAfterAPoorPredictorWhenAsked) {
  ChainProblem far(100);
  SparseCholesky held;
  solve_and_factorize(far, held);
  far.scale_load(3.0);
  NewtonSolver solver;
  ChordSteps chords{&held, false};
  chords.stop_after_poor_predictor = true;
  const double start_force = far.force_norm(far.gradient());
  const NewtonReport stopped = solver.solve(far, chords);
  EXPECT_FALSE(stopped.converged);
  EXPECT_TRUE(stopped.stopped_after_predictor);
  EXPECT_EQ(stopped.factorizations, 0);
  ASSERT_EQ(stopped.history.size(), 1u);
  EXPECT_TRUE(stopped.history.front().chord);
  const NewtonIteration& predictor = stopped.history.front();
  EXPECT_TRUE(predictor.step_size < 1.0 ||
              stopped.final_force_norm > solver.options().chord_contraction * start_force);
  EXPECT_NE(stopped.message.find("predictor"), std::string::npos) << stopped.message;
  // The rest of the solve from there converges as usual.
  const NewtonReport rest = solver.solve(far, {&held, false});
  EXPECT_TRUE(rest.converged);
  EXPECT_FALSE(rest.stopped_after_predictor);

  ChainProblem near(100);
  SparseCholesky near_held;
  solve_and_factorize(near, near_held);
  near.scale_load(1.001);
  ChordSteps near_chords{&near_held, false};
  near_chords.stop_after_poor_predictor = true;
  const NewtonReport r = solver.solve(near, near_chords);
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.stopped_after_predictor);
  EXPECT_EQ(r.factorizations, 0);
}

TEST(NewtonSolver, ReusingItsOwnFactorizationsSavesFactorizations) {
  ChainProblem plain_problem(200), reuse_problem(200);
  NewtonSolver plain, reuse;
  const NewtonReport p = plain.solve(plain_problem);
  const NewtonReport r = reuse.solve(reuse_problem, {nullptr, true});
  ASSERT_TRUE(p.converged);
  ASSERT_TRUE(r.converged);
  EXPECT_GT(r.chord_steps, 0);
  EXPECT_LT(r.factorizations, p.factorizations);
  EXPECT_LT((plain_problem.q() - reuse_problem.q()).norm(), 1e-8 * plain_problem.q().norm());
}

/// The chain with a Hessian operator: Newton–Krylov chord steps are possible.
class OperatorChainProblem : public ChainProblem {
 public:
  using ChainProblem::ChainProblem;
  std::optional<LinearOperator> hessian_operator() override {
    return LinearOperator([H = hessian()](const VecX& v) { return VecX(H * v); });
  }
};

TEST(NewtonSolver, KrylovChordStepsConvergeWithFewerFactorizations) {
  // After a design step too large for plain chord steps to contract fast, conjugate
  // gradients on the current Newton system, preconditioned by the held factorization,
  // reach the same equilibrium with fewer factorizations.
  OperatorChainProblem krylov_problem(200), chord_problem(200);
  SparseCholesky held_k, held_c;
  solve_and_factorize(krylov_problem, held_k);
  solve_and_factorize(chord_problem, held_c);
  krylov_problem.scale_load(1.3);
  chord_problem.scale_load(1.3);
  NewtonOptions plain_chords;
  plain_chords.krylov_chords = false;
  NewtonSolver krylov, chords(plain_chords);
  const NewtonReport k = krylov.solve(krylov_problem, {&held_k, true});
  const NewtonReport c = chords.solve(chord_problem, {&held_c, true});
  ASSERT_TRUE(k.converged);
  ASSERT_TRUE(c.converged);
  EXPECT_GT(k.krylov_iterations, 0);
  EXPECT_EQ(c.krylov_iterations, 0);
  EXPECT_LT(k.factorizations, c.factorizations);
  EXPECT_LT((krylov_problem.q() - chord_problem.q()).norm(), 1e-8 * chord_problem.q().norm());
}

TEST(NewtonSolver, KrylovToleranceFollowsTheForceDecrease) {
  // Eisenstat–Walker forcing: loose CG tolerances while the force falls slowly, never
  // below krylov_tolerance nor above krylov_max_tolerance, the first step at
  // krylov_tolerance; the same equilibrium as with a fixed tolerance.
  OperatorChainProblem forced_problem(200), fixed_problem(200);
  SparseCholesky held_forced, held_fixed;
  solve_and_factorize(forced_problem, held_forced);
  solve_and_factorize(fixed_problem, held_fixed);
  forced_problem.scale_load(3.0);
  fixed_problem.scale_load(3.0);
  NewtonOptions fixed_options;
  fixed_options.krylov_forcing = 0.0;
  NewtonSolver forced, fixed(fixed_options);
  const NewtonReport f = forced.solve(forced_problem, {&held_forced, true});
  const NewtonReport x = fixed.solve(fixed_problem, {&held_fixed, true});
  ASSERT_TRUE(f.converged);
  ASSERT_TRUE(x.converged);
  const NewtonOptions& o = forced.options();
  ASSERT_FALSE(f.history.empty());
  EXPECT_EQ(f.history.front().krylov_tolerance, o.krylov_tolerance);
  bool loosened = false;
  for (const NewtonIteration& it : f.history) {
    EXPECT_GE(it.krylov_tolerance, o.krylov_tolerance);
    EXPECT_LE(it.krylov_tolerance, o.krylov_max_tolerance);
    loosened = loosened || it.krylov_tolerance > o.krylov_tolerance;
  }
  EXPECT_TRUE(loosened);
  for (const NewtonIteration& it : x.history) EXPECT_EQ(it.krylov_tolerance, o.krylov_tolerance);
  EXPECT_LT((forced_problem.q() - fixed_problem.q()).norm(), 1e-8 * fixed_problem.q().norm());
}

TEST(NewtonSolver, IgnoresAHeldFactorizationOfAnotherSize) {
  ChainProblem small(10);
  SparseCholesky held;
  solve_and_factorize(small, held);
  ChainProblem problem(20);
  NewtonSolver solver;
  const NewtonReport r = solver.solve(problem, {&held, false});
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.chord_steps, 0);
}

/// Rosenbrock: indefinite Hessian away from the valley, needs regularization.
class RosenbrockProblem : public VectorProblem {
 public:
  RosenbrockProblem() : VectorProblem(Eigen::Vector2d(0.5, 1.0)) {}  // H indefinite here
  double energy() override {
    const double x = q_[0], y = q_[1];
    return (1 - x) * (1 - x) + 100 * (y - x * x) * (y - x * x);
  }
  VecX gradient() override {
    const double x = q_[0], y = q_[1];
    return Eigen::Vector2d(-2 * (1 - x) - 400 * x * (y - x * x), 200 * (y - x * x));
  }
  SparseMatrix hessian() override {
    const double x = q_[0], y = q_[1];
    Eigen::Matrix2d H;
    H << 2 - 400 * (y - 3 * x * x), -400 * x, -400 * x, 200;
    return H.sparseView();
  }
};

TEST(NewtonSolver, RegularizesIndefiniteHessians) {
  RosenbrockProblem problem;
  NewtonSolver solver;
  const NewtonReport r = solver.solve(problem);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(problem.q()[0], 1.0, 1e-8);
  EXPECT_NEAR(problem.q()[1], 1.0, 1e-8);
  bool regularized = false;
  for (const auto& it : r.history) regularized |= it.regularization > 0.0;
  EXPECT_TRUE(regularized);
}

/// A barrier: energy is +inf for q <= 0 (like an inverted element); minimum at q = 1
/// of U = q − log q. Newton from q = 0.05 overshoots into q < 0 and must back off.
class BarrierProblem : public VectorProblem {
 public:
  BarrierProblem() : VectorProblem(VecX::Constant(1, 0.05)) {}
  double energy() override {
    return q_[0] <= 0 ? std::numeric_limits<double>::infinity() : q_[0] - std::log(q_[0]);
  }
  VecX gradient() override { return VecX::Constant(1, 1.0 - 1.0 / q_[0]); }
  SparseMatrix hessian() override {
    SparseMatrix H(1, 1);
    H.insert(0, 0) = 1.0 / (q_[0] * q_[0]);
    return H;
  }
};

TEST(NewtonSolver, LineSearchRejectsInadmissibleStates) {
  BarrierProblem problem;
  NewtonSolver solver;
  const NewtonReport r = solver.solve(problem);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(problem.q()[0], 1.0, 1e-9);
}

/// A state on the unit circle: the step is an angle; U = −cos(θ − θ*). set_step refuses
/// steps longer than 0.3 rad, as a garment vertex walk might.
class CircleProblem : public NewtonProblem {
 public:
  Eigen::Index num_dofs() const override { return 1; }
  double energy() override { return -std::cos(theta_ - target_); }
  VecX gradient() override { return VecX::Constant(1, std::sin(theta_ - target_)); }
  SparseMatrix hessian() override {
    SparseMatrix H(1, 1);
    H.insert(0, 0) = std::max(std::cos(theta_ - target_), 1e-3);
    return H;
  }
  bool set_step(const VecX& dq, double alpha) override {
    if (std::abs(alpha * dq[0]) > 0.3) return false;
    theta_ = base_ + alpha * dq[0];
    return true;
  }
  void commit() override { base_ = theta_; }
  double theta_ = 0.0, base_ = 0.0, target_ = 1.2;
};

TEST(NewtonSolver, ShortensStepsTheProblemRefuses) {
  CircleProblem problem;
  NewtonSolver solver;
  const NewtonReport r = solver.solve(problem);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(problem.theta_, 1.2, 1e-9);
}

/// The chain whose energy carries a term its gradient does not: −eps·‖q − q*‖ (q*: the
/// zero of the gradient). Every step towards q* raises the energy by eps per unit length
/// more than the gradient predicts, as a garment pressing on the body does where the
/// limit surface's derivatives are not exactly those of its positions; close to q* that
/// rise is larger than the decrease the gradient promises.
class InconsistentChainProblem : public ChainProblem {
 public:
  InconsistentChainProblem(int n, double eps, VecX solution)
      : ChainProblem(n), eps_(eps), solution_(std::move(solution)) {}
  double energy() override { return ChainProblem::energy() - eps_ * (q_ - solution_).norm(); }

 private:
  double eps_;
  VecX solution_;
};

TEST(NewtonSolver, AcceptsFullStepsByForceWhereTheEnergyCannotTell) {
  ChainProblem exact(20);
  ASSERT_TRUE(NewtonSolver().solve(exact).converged);
  NewtonOptions options;
  options.max_iterations = 30;
  options.throw_on_failure = false;
  InconsistentChainProblem problem(20, 1e-5, exact.q());
  const NewtonReport r = NewtonSolver(options).solve(problem);
  ASSERT_TRUE(r.converged) << r.message << ", force " << r.final_force_norm;
  EXPECT_GT(r.force_accepted_steps, 0);
  EXPECT_LE(r.iterations, 10);
  EXPECT_LT((problem.q() - exact.q()).norm(), 1e-8);

  // The energy test alone crawls on the short steps the round-off allowance lets through.
  options.force_merit_contraction = 0.0;
  InconsistentChainProblem stalled(20, 1e-5, exact.q());
  const NewtonReport s = NewtonSolver(options).solve(stalled);
  EXPECT_EQ(s.force_accepted_steps, 0);
  EXPECT_GE(s.iterations, 2 * r.iterations);
}

/// U = ½q² + h·exp(−q²/(2w²)): a narrow bump on a parabola, a maximum at q = 0 and minima
/// where exp(−q²/(2w²)) = w²/h. From q = 1 (positive curvature, the bump invisible) the
/// full Newton step lands on the bump's top, where the force is zero but the energy is
/// higher by far more than round-off: that step must not be accepted by its force.
class BumpProblem : public VectorProblem {
 public:
  BumpProblem() : VectorProblem(VecX::Constant(1, 1.0)) {}
  double energy() override { return 0.5 * q_[0] * q_[0] + kH * bump(); }
  VecX gradient() override { return VecX::Constant(1, q_[0] * (1.0 - kH / (kW * kW) * bump())); }
  SparseMatrix hessian() override {
    const double q = q_[0], b = bump();
    SparseMatrix H(1, 1);
    H.insert(0, 0) = 1.0 - kH / (kW * kW) * b * (1.0 - q * q / (kW * kW));
    return H;
  }
  static constexpr double kH = 1.0, kW = 0.1;

 private:
  double bump() const { return std::exp(-q_[0] * q_[0] / (2 * kW * kW)); }
};

TEST(NewtonSolver, DoesNotAcceptAnEnergyRiseByForce) {
  BumpProblem problem;
  const NewtonReport r = NewtonSolver().solve(problem);
  ASSERT_TRUE(r.converged);
  const double minimum =
      BumpProblem::kW *
      std::sqrt(2.0 * std::log(BumpProblem::kH / (BumpProblem::kW * BumpProblem::kW)));
  EXPECT_NEAR(problem.q()[0], minimum, 1e-9);
  EXPECT_EQ(r.force_accepted_steps, 0);
}

/// Unbounded below: U = −q³ − q has no minimum; Newton must fail loudly.
class UnboundedProblem : public VectorProblem {
 public:
  UnboundedProblem() : VectorProblem(VecX::Constant(1, 1.0)) {}
  double energy() override { return -q_[0] * q_[0] * q_[0] - q_[0]; }
  VecX gradient() override { return VecX::Constant(1, -3 * q_[0] * q_[0] - 1); }
  SparseMatrix hessian() override {
    SparseMatrix H(1, 1);
    H.insert(0, 0) = -6 * q_[0];
    return H;
  }
};

TEST(NewtonSolver, ReportsFailureWithTheResidual) {
  UnboundedProblem problem;
  NewtonOptions options;
  options.max_iterations = 20;
  NewtonSolver solver(options);
  try {
    solver.solve(problem);
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("force residual"), std::string::npos) << e.what();
  }
  options.throw_on_failure = false;
  UnboundedProblem again;
  const NewtonReport r = NewtonSolver(options).solve(again);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(std::isfinite(r.final_force_norm));
}

}  // namespace tightfit::newton_solver_test
