#pragma once
/// The coupled cloth–body system of paper Sec. 3.3 as a Newton problem.
/// Garment vertex i lives on the body's Loop limit surface at s_i = (face, u, v);
/// its position is x_i = Σ_k L_k(s_i) y_k (Eq. 18) over the body's surface vertices
/// y_k. Degrees of freedom q = (s, y): two parameter-domain coordinates per free
/// garment vertex, then three coordinates per free body vertex. Energies on x (cloth,
/// seams) are pulled back by the chain rule (Eq. 19) including the second-derivative
/// terms of Eq. 18; energies on y (the body) are added directly. Steps move garment
/// vertices across faces by walking in the parameter domain (Eq. 20).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tightfit/physics/energy.hpp"
#include "tightfit/solve/coupled_hessian.hpp"
#include "tightfit/solve/newton_problem.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

/// Positions of the coupled system: garment vertices on the surface, body vertices in space.
struct EmbeddedState {
  std::vector<SurfacePoint> garment;  ///< n_g surface points
  Points3 body;                       ///< n_b×3 deformed body positions (m)
};

/// The layouts of the garment energies' (H_xx) and the body energies' Hessian triplets.
struct HessianLayouts {
  std::shared_ptr<const BlockLayout> garment, body;
};

/// Which Hessian of the total energy to assemble. Both have the same sparsity pattern
/// (zeros are stored), so one symbolic factorization serves both.
enum class HessianKind {
  kNewton,  ///< as Newton uses it: cloth/seam element Hessians PSD-projected when the
            ///< setup asks for it (EmbeddedSystemSetup::project_garment_hessians)
  kExact,   ///< the exact ∂g/∂q, no projection (the adjoint's matrix)
};

struct EmbeddedSystemSetup {
  const LimitSurface* surface = nullptr;        ///< limit surface of the body's surface mesh
  std::vector<const Energy*> garment_energies;  ///< functions of x (3·n_g)
  std::vector<const Energy*> body_energies;     ///< functions of y (3·n_b)
  std::vector<int> pinned_body;                 ///< body vertices held at their position
  std::vector<int> pinned_garment;              ///< garment vertices held at their (face,u,v)
  double force_scale = 1.0;                     ///< characteristic force (N) for tolerances
  bool project_garment_hessians = true;         ///< per-element PSD projection of cloth terms
  /// Optional: what a garment vertex belongs to, for messages (e.g. "piece 'front'").
  std::function<std::string(int garment_vertex)> garment_vertex_label;
  /// Where the energies' Hessian triplets go (BlockLayout), shared by the problems made
  /// for the same garment and body one after the other (a new rest shape, a new state),
  /// so that it is analysed once; made and kept up to date here when null.
  std::shared_ptr<HessianLayouts> hessian_layouts;
};

class EmbeddedEquilibrium : public NewtonProblem {
 public:
  EmbeddedEquilibrium(EmbeddedSystemSetup setup, EmbeddedState initial);

  Eigen::Index num_dofs() const override { return num_dofs_; }
  double energy() override;
  VecX gradient() override;
  /// The Newton Hessian (HessianKind::kNewton).
  SparseMatrix hessian() override { return hessian(HessianKind::kNewton); }
  /// The product with the Newton Hessian at the current state, v ↦ Jᵀ(H_xx (J v)) + E v,
  /// from its factors (no sparse matrix product).
  std::optional<LinearOperator> hessian_operator() override {
    return hessian_operator(HessianKind::kNewton);
  }
  /// The product with the Hessian of the given kind at the current state, from its
  /// factors (J, H_xx, E: no sparse matrix product is formed).
  LinearOperator hessian_operator(HessianKind kind);
  /// The Hessian of the given kind at the current state (num_dofs × num_dofs, N/m, both
  /// triangles stored, the pattern independent of the state and of the kind).
  SparseMatrix hessian(HessianKind kind);
  /// True when kNewton projects element Hessians (so kNewton and kExact may differ).
  bool projects_hessians() const { return setup_.project_garment_hessians; }
  /// Walks every free garment vertex by alpha·dq on the surface and moves the body
  /// vertices. Returns false when a walk ran into a surface vertex it could not pass
  /// (the state then holds the walk's end there; Newton's line search shortens the step).
  bool set_step(const VecX& dq, double alpha) override;
  void commit() override;
  double force_norm(const VecX& gradient) override;
  /// The free garment vertex (tangential force) or body vertex with the largest force,
  /// with its label (setup), index and position.
  std::string locate_largest_force(const VecX& gradient) override;
  /// The forces (N) the current state leaves unbalanced, −gradient() per vertex: per
  /// garment vertex the tangential force −J_s (J_sᵀJ_s)⁻¹ g_s (n_g×3; zero rows for
  /// pinned vertices), per body vertex −g_y (n_b×3; zero rows for pinned ones). Zero
  /// at an equilibrium; where a solve did not converge, the map of where it failed.
  Points3 garment_residual_forces() const;
  Points3 body_residual_forces() const;
  double force_scale() override { return setup_.force_scale; }

  const EmbeddedState& state() const { return state_; }
  /// Garment positions x (n_g×3, m) at the current state.
  const Points3& garment_positions() const { return x_; }
  /// What garment vertex i belongs to, for messages ("piece 'front'"; empty when the
  /// setup gives no labels).
  std::string garment_vertex_label(int i) const;
  /// dU/dx (3·n_g) at the current state: minus the elastic forces on garment vertices.
  VecX garment_energy_gradient() const;
  /// Sparse Jacobian dx/dq (3·n_g × num_dofs) at the current state.
  SparseMatrix position_jacobian() const;
  /// Index of the first DOF of garment vertex i (−1 when pinned) / body vertex k.
  int garment_dof(int i) const { return garment_dof_[i]; }
  int body_dof(int k) const { return body_dof_[k]; }
  int num_garment_vertices() const { return static_cast<int>(state_.garment.size()); }
  /// Unit outward surface normal at garment vertex i.
  Vec3 garment_normal(int i) const;

 private:
  /// The factors of the Hessian of the given kind at the current state
  /// (coupled_hessian.hpp: H = Jᵀ H_xx J + E).
  CoupledHessianFactors hessian_factors(HessianKind kind) const;
  void evaluate_garment();      // stencils, x, derivatives at the current state
  VecX total_gradient() const;  // gradient() (the interface's is not const)
  Eigen::Matrix<double, 3, 2> tangent_basis(int garment_vertex) const;              // [x_u x_v]
  double tangential_force_squared(int garment_vertex, const VecX& gradient) const;  // N²
  double garment_energy(const VecX& x) const;

  EmbeddedSystemSetup setup_;
  EmbeddedState base_;
  EmbeddedState state_;
  std::vector<int> garment_dof_;
  std::vector<int> body_dof_;
  Eigen::Index num_dofs_ = 0;
  int num_control_ = 0;

  // Evaluated at the current state.
  std::vector<LimitWeights> weights_;
  Points3 x_, xu_, xv_, xuu_, xuv_, xvv_;
};

}  // namespace tightfit
