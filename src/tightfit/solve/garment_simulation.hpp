#pragma once
/// Forward simulation of a garment on a body (paper Sec. 3): builds the energies
/// (relaxed StVK cloth, seam springs, Neo-Hookean body), the embedded equilibrium
/// problem and Newton's method, and analyses the fit (stretches, regimes, stresses,
/// pressure by Eq. 31 with two shape operators, and per-vertex forces on the body).
#include <memory>
#include <optional>

#include "tightfit/body/body.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/physics/cloth_analysis.hpp"
#include "tightfit/physics/garment_energies.hpp"
#include "tightfit/physics/neo_hookean_energy.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"
#include "tightfit/solve/newton_solver.hpp"

namespace tightfit {

struct SimulationMaterials {
  ClothMaterial fabric;
  /// Seam springs (Eq. 12); none when seam.youngs_modulus is 0.
  SeamMaterial seam{0.005, 2e-4, 0.0};
  NeoHookeanMaterial body;
  /// Hold every body vertex in place (a rigid body): only the garment moves.
  bool rigid_body = false;
};

/// Which discrete shape operator the pressure of Eq. 31 uses by default.
enum class ShapeOperatorKind { kMidEdge, kLimitSurface };

/// The fit at an equilibrium. Per-element arrays follow the garment triangles.
struct FitAnalysis {
  std::vector<ClothElementFit> elements;
  VecX pressure_mid_edge;    ///< Pa per element, Λ from mid-edge normals (Eq. 32-33)
  VecX pressure_limit;       ///< Pa per element, Λ from the limit surface's exact curvature
  VecX vertex_pressure;      ///< Pa per garment vertex: normal force / mixed Voronoi area
  Points3 vertex_force;      ///< N per garment vertex: force the cloth exerts on the body
  VecX vertex_normal_force;  ///< N per garment vertex: its component along the outward normal
  Points3 vertex_normal;     ///< unit outward limit-surface normal per garment vertex
};

class GarmentSimulation {
 public:
  /// `surface` must be the limit surface of `body.surface` and outlive this object.
  /// The garment's embedding is the initial state; the body starts at rest.
  GarmentSimulation(const Body& body, const LimitSurface& surface, Garment garment,
                    SimulationMaterials materials, NewtonOptions newton = {});
  ~GarmentSimulation();

  /// Newton from the current state (warm start). Throws SolverError if it fails.
  /// `chords`: factorizations Newton may reuse for chord steps (NewtonSolver::solve);
  /// by default each Newton step's own (Newton–Krylov chord steps after it while they
  /// contract: the same equilibrium to the tolerance with fewer factorizations).
  /// With a deformable body and garment_first() on, the garment is first relaxed on the
  /// body held still (relax_garment_on_still_body) where the coupled Newton would start
  /// far from its equilibrium: always without a held factorization (a cold start: the
  /// initial placement, a remeshed garment); with one (a warm start after a design
  /// step), when its predictor step contracts the force poorly
  /// (ChordSteps::stop_after_poor_predictor). The returned report counts all stages in
  /// order (NewtonReport::garment_first_iterations, NewtonIteration::body_held).
  NewtonReport solve(ChordSteps chords = {nullptr, true});
  /// Whether solves relax the garment on the still body first where they start far from
  /// the equilibrium (default on).
  bool garment_first() const { return garment_first_; }
  void set_garment_first(bool on) { garment_first_ = on; }
  /// Newton on the garment's surface coordinates alone, every body vertex held at its
  /// current position, to a relative force tolerance of `kGarmentFirstTolerance` in at
  /// most `kGarmentFirstIterations` factorizing steps; the state it reaches (never of
  /// higher energy: the body energy is unchanged and Newton only descends) becomes the
  /// current state. The system is the garment's (2 DOFs per vertex, a surface mesh's
  /// sparsity), far cheaper to factorize than the coupled one, and takes the large
  /// sliding of a cold start, so that the coupled solve starts where only the body's
  /// response is left. Its report's steps are all body_held (garment_first_iterations =
  /// iterations).
  NewtonReport relax_garment_on_still_body();
  static constexpr double kGarmentFirstTolerance = 1e-6;
  static constexpr int kGarmentFirstIterations = 30;

  const Garment& garment() const { return garment_; }
  const Body& body() const { return body_; }
  const LimitSurface& surface() const { return surface_; }
  const SimulationMaterials& materials() const { return materials_; }
  EmbeddedEquilibrium& problem() { return *problem_; }
  const EmbeddedEquilibrium& problem() const { return *problem_; }
  NewtonSolver& newton() { return newton_; }
  const ClothEnergy& cloth() const { return energies_->cloth(); }
  /// Seam springs, or null when the seam material is off or the garment has no seams.
  const SeamSpringEnergy* seams() const { return energies_->seams(); }
  const NeoHookeanEnergy& body_energy() const { return *body_energy_; }
  /// The energies of the equilibrium problem that depend on the pattern rest positions
  /// (cloth, and the seam springs when present): exactly its garment energies.
  std::vector<const RestDependentEnergy*> rest_dependent_energies() const {
    return energies_->all();
  }
  /// The pattern rest positions Xbar (num_pattern_vertices×2, m): the ONE array the
  /// garment energies read. The garment's pattern pieces carry the same values piece by
  /// piece for the outputs (both written by set_rest_positions only).
  const Points2& rest_positions() const { return *rest_; }

  /// Current garment positions (n_g×3, m) and deformed body (n_b×3, m).
  const Points3& garment_positions() const { return problem_->garment_positions(); }
  const Points3& body_positions() const { return problem_->state().body; }
  /// Replaces the pattern rest positions (stacked, num_pattern_vertices×2, m): the rest
  /// array the energies read and the garment's pieces; the state is kept (warm start).
  /// Throws InputError, changing nothing, when an element would be degenerate.
  void set_rest_positions(const Points2& rest);
  /// Replaces the state (e.g. to restore a checkpoint).
  void set_state(const EmbeddedState& state);
  /// Replaces the garment by another one on the same body (a remeshed pattern, with
  /// other vertex counts and triangles) at `state` (one surface point per garment
  /// vertex of `garment`, one position per body vertex): rebuilds the cloth and seam
  /// energies, the force scale and the equilibrium problem; materials and Newton
  /// options are kept. Throws InputError when the sizes do not match.
  void replace_garment(Garment garment, const EmbeddedState& state);

  /// Analyses the fit at the current state.
  FitAnalysis analyze() const;

  /// Characteristic force E·t·(mean rest edge length) (N), used for the tolerance.
  double force_scale() const { return force_scale_; }

 private:
  void rebuild_problem(const EmbeddedState& state);
  /// relax_garment_on_still_body() as a stage of solve(): an empty report (state
  /// unchanged) where it threw.
  NewtonReport relax_garment_stage();
  /// The equilibrium problem's setup for the current garment and materials (all body
  /// vertices pinned when `still_body`).
  EmbeddedSystemSetup problem_setup(bool still_body);
  /// Takes `garment` with its rest array and energies; changes nothing if they throw.
  void adopt_garment(Garment garment);
  /// "piece 'NAME'" (or "pieces 'A', 'B'" on a seam) of a garment vertex, for messages.
  std::string garment_vertex_piece(int vertex) const;

  const Body& body_;
  const LimitSurface& surface_;
  Garment garment_;
  SimulationMaterials materials_;
  NewtonSolver newton_;
  std::unique_ptr<Points2> rest_;  // the one rest array (its own allocation: energies bind to it)
  std::unique_ptr<GarmentEnergies> energies_;
  std::unique_ptr<NeoHookeanEnergy> body_energy_;
  std::unique_ptr<EmbeddedEquilibrium> problem_;
  // Shared by every problem_ this simulation makes (EmbeddedSystemSetup::hessian_layouts).
  std::shared_ptr<HessianLayouts> hessian_layouts_ = std::make_shared<HessianLayouts>();
  double force_scale_ = 1.0;
  bool garment_first_ = true;
};

}  // namespace tightfit
