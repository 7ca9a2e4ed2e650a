#pragma once
/// The contract every energy (physics/energy.hpp, physics/rest_dependent_energy.hpp) and
/// every design term (design/design_term.hpp) keeps, checked in one place so that the
/// lists in tests/physics/energy_contract_test.cpp and
/// tests/objectives/design_term_contract_test.cpp run the same checks on each:
///  * the gradient is the derivative of the value and the Hessian that of the gradient
///    (the shared finite-difference helper, fourth order);
///  * the Hessian is symmetric, and its sparsity pattern (the (row, column) pairs of the
///    triplets written) does not depend on the state: Newton analyses a pattern once per
///    topology;
///  * the PSD-projected Hessian has the same pattern and no negative eigenvalue;
///  * rest-dependent energies: ∂U/∂Xbar and ∂²U/∂x∂Xbar are the derivatives of U and of
///    ∂U/∂x in the rest positions;
///  * design terms: ∂T/∂x and ∂T/∂Xbar are the derivatives of T, and a term that says it
///    does not depend on positions has ∂T/∂x = 0.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "support/energy_assembly.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/physics/assembly.hpp"
#include "tightfit/physics/rest_dependent_energy.hpp"

namespace tightfit::test {

/// Steps and relative tolerances of the contract checks.
struct ContractTolerances {
  double step = 1e-6;        ///< finite-difference step (units of the variable)
  double derivative = 1e-6;  ///< relative error of every first and second derivative
  double symmetry = 1e-12;   ///< ‖H − Hᵀ‖_F / ‖H‖_F
  double psd = 1e-9;         ///< smallest projected eigenvalue ≥ −psd · largest
};

/// The (row, column) pairs of a triplet list, each once.
inline std::set<std::pair<int, int>> triplet_pattern(const std::vector<Triplet>& triplets) {
  std::set<std::pair<int, int>> out;
  for (const Triplet& t : triplets)
    out.insert({static_cast<int>(t.row()), static_cast<int>(t.col())});
  return out;
}

/// Checks value, gradient and Hessian of `energy` at x, and the Hessian's pattern at x
/// against its pattern at `other` (another state of the same size, e.g. x moved).
inline void expect_energy_contract(const Energy& energy, const VecX& x, const VecX& other,
                                   const ContractTolerances& tol = {}) {
  SCOPED_TRACE("energy '" + energy.name() + "'");
  ASSERT_EQ(other.size(), x.size());
  const VecX g = test::energy_gradient(energy, x);
  EXPECT_LT(
      check_gradient([&](const VecX& y) { return energy.value(y); }, g, x, tol.step).relative_error,
      tol.derivative)
      << "gradient";
  const MatX H = MatX(test::energy_hessian(energy, x));
  EXPECT_LT(
      check_hessian([&](const VecX& y) { return test::energy_gradient(energy, y); }, H, x, tol.step)
          .relative_error,
      tol.derivative)
      << "Hessian";
  EXPECT_LE((H - H.transpose()).norm(), tol.symmetry * std::max(H.norm(), 1e-300)) << "symmetry";

  std::vector<Triplet> at_x, at_other, projected;
  energy.add_hessian(x, at_x);
  energy.add_hessian(other, at_other);
  energy.add_hessian(x, projected, true);
  EXPECT_EQ(triplet_pattern(at_x), triplet_pattern(at_other))
      << "the Hessian's sparsity pattern changes with the state";
  EXPECT_EQ(triplet_pattern(at_x), triplet_pattern(projected))
      << "the projected Hessian has another sparsity pattern";
  const MatX P = MatX(test::sparse_from_triplets(x.size(), x.size(), projected));
  const Eigen::SelfAdjointEigenSolver<MatX> eigen(0.5 * (P + P.transpose()));
  EXPECT_GE(eigen.eigenvalues().minCoeff(),
            -tol.psd * std::max(eigen.eigenvalues().cwiseAbs().maxCoeff(), 1e-300))
      << "the projected Hessian is not positive semi-definite";
}

/// Checks the rest derivatives of `energy` at positions x and its current rest shape
/// (restored on return).
inline void expect_rest_dependent_contract(RestDependentEnergy& energy, const VecX& x,
                                           const ContractTolerances& tol = {}) {
  SCOPED_TRACE("rest-dependent energy '" + energy.name() + "'");
  const Points2& bound = energy.rest();
  const Points2 rest0 = bound;
  const VecX xbar = Eigen::Map<const VecX>(rest0.data(), rest0.size());
  Points2 trial = rest0;
  auto with_rest = [&](const VecX& v, auto evaluate) {
    trial = Eigen::Map<const Points2>(v.data(), rest0.rows(), 2);
    energy.bind_rest(trial);
    auto r = evaluate();
    energy.bind_rest(bound);
    return r;
  };
  VecX g_rest = VecX::Zero(xbar.size());
  energy.add_gradient_rest(x, g_rest);
  EXPECT_LT(
      check_gradient([&](const VecX& v) { return with_rest(v, [&] { return energy.value(x); }); },
                     g_rest, xbar, tol.step)
          .relative_error,
      tol.derivative)
      << "∂U/∂Xbar";
  std::vector<Triplet> mixed;
  energy.add_mixed_rest(x, mixed);
  EXPECT_LT(check_jacobian(
                [&](const VecX& v) {
                  return with_rest(v, [&] { return test::energy_gradient(energy, x); });
                },
                MatX(test::sparse_from_triplets(x.size(), xbar.size(), mixed)), xbar, tol.step)
                .relative_error,
            tol.derivative)
      << "∂²U/∂x∂Xbar";
}

/// Checks ∂T/∂x and ∂T/∂Xbar of `term` at (x, rest) with the optional embedding.
inline void expect_design_term_contract(const DesignTerm& term, const VecX& x, const Points2& rest,
                                        const DesignEmbedding* embedding = nullptr,
                                        const ContractTolerances& tol = {}) {
  SCOPED_TRACE("design term '" + term.name() + "'");
  VecX d_x = VecX::Zero(x.size());
  VecX d_rest = VecX::Zero(rest.size());
  term.add_gradient(DesignState{x, rest, embedding}, d_x, d_rest);
  const double floor = 1e-10 * std::max(1.0, std::abs(term.value(DesignState{x, rest, embedding})));
  EXPECT_LT(check_gradient(
                [&](const VecX& y) {
                  return term.value(DesignState{y, rest, embedding});
                },
                d_x, x, tol.step, floor)
                .relative_error,
            tol.derivative)
      << "∂T/∂x";
  if (!term.depends_on_positions()) {
    EXPECT_EQ(d_x.norm(), 0.0) << "∂T/∂x of a rest-only term";
  }
  const VecX xbar = Eigen::Map<const VecX>(rest.data(), rest.size());
  EXPECT_LT(check_gradient(
                [&](const VecX& v) {
                  const Points2 r = Eigen::Map<const Points2>(v.data(), rest.rows(), 2);
                  return term.value(DesignState{x, r, embedding});
                },
                d_rest, xbar, tol.step, floor)
                .relative_error,
            tol.derivative)
      << "∂T/∂Xbar";
}

}  // namespace tightfit::test
