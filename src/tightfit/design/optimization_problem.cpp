#include "tightfit/design/optimization_problem.hpp"

#include "tightfit/design/finite_state.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/common/stopwatch.hpp"

namespace tightfit {
namespace {

/// Per piece: the quality of its mesh as it is.
std::vector<PieceQuality> fresh_qualities(const Pattern& pattern) {
  std::vector<PieceQuality> out;
  for (const PatternPiece& piece : pattern.pieces) out.push_back(piece_quality(piece));
  return out;
}

/// Per piece: its rest positions.
std::vector<Points2> mesh_rest_positions(const Pattern& pattern) {
  std::vector<Points2> out;
  for (const PatternPiece& piece : pattern.pieces) out.push_back(piece.rest);
  return out;
}

VecX signed_areas(const Triangles& triangles, const Points2& rest) {
  VecX a(triangles.rows());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    a[t] = signed_area(rest.row(triangles(t, 0)), rest.row(triangles(t, 1)),
                       rest.row(triangles(t, 2)));
  }
  return a;
}

}  // namespace

DesignProblem::DesignProblem(GarmentSimulation& sim, std::shared_ptr<const DesignTermSum> objective,
                             DesignProblemOptions options, ObjectiveFactory make_objective)
    : sim_(sim),
      options_(options),
      adjoint_(options.adjoint),
      make_objective_(std::move(make_objective)),
      ref_(make_reference(std::move(objective), BiharmonicCoordinates(sim.garment().pattern),
                          fresh_qualities(sim.garment().pattern),
                          mesh_rest_positions(sim.garment().pattern))) {
  if (!ref_.objective) throw std::invalid_argument("DesignProblem: null objective");
  if (options_.remesh.edge_length < 0.0 || !(options_.remesh.min_area_fraction >= 0.0) ||
      !(options_.remesh.min_angle_deg >= 0.0 && options_.remesh.min_angle_deg < 60.0) ||
      options_.remesh.smoothing_iterations < 0)
    throw std::invalid_argument("DesignProblem: invalid remesh options");
  for (const PatternPiece& piece : sim_.garment().pattern.pieces)
    target_edge_.push_back(options_.remesh.edge_length > 0.0 ? options_.remesh.edge_length
                                                             : mean_edge_length(piece));
  accept_reference();
}

DesignProblem::Reference DesignProblem::make_reference(
    std::shared_ptr<const DesignTermSum> objective, BiharmonicCoordinates coordinates,
    std::vector<PieceQuality> fresh, std::vector<Points2> mesh_rest) const {
  const Garment& g = sim_.garment();
  Reference ref{
      std::move(objective), std::move(coordinates), g.rest_positions(), VecX(), VecX(), 0.0,
      std::move(fresh),     std::move(mesh_rest)};
  ref.initial_parameters = ref.coordinates.parameters(ref.initial_rest);
  ref.initial_areas = signed_areas(g.topology->pattern_triangles, ref.initial_rest);
  double sum = 0.0;
  int count = 0;
  for (const PatternPiece& piece : g.pattern.pieces)
    for (size_t k = 0; k < piece.boundary.size(); ++k, ++count)
      sum += (piece.rest.row(piece.boundary[k]) -
              piece.rest.row(piece.boundary[(k + 1) % piece.boundary.size()]))
                 .norm();
  ref.mean_boundary_edge = count > 0 ? sum / count : 0.0;
  return ref;
}

void DesignProblem::accept_reference() {
  accepted_p_ = ref_.initial_parameters;
  current_p_ = ref_.initial_parameters;
  accepted_state_ = sim_.problem().state();
  last_ok_ = false;
  gradient_generation_ = -1;
  accepted_generation_ = -1;
}

Points2 DesignProblem::rest_positions(const VecX& p) const { return rest_positions_at(ref_, p); }

Points2 DesignProblem::rest_positions_at(const Reference& ref, const VecX& p) const {
  if (p.size() != ref.coordinates.num_parameters())
    throw std::invalid_argument("DesignProblem: parameter vector has the wrong length");
  return ref.initial_rest + ref.coordinates.rest_positions(VecX(p - ref.initial_parameters));
}

double DesignProblem::min_area_ratio(const VecX& p) const { return min_area_ratio_at(ref_, p); }

double DesignProblem::min_area_ratio_at(const Reference& ref, const VecX& p) const {
  const VecX a =
      signed_areas(sim_.garment().topology->pattern_triangles, rest_positions_at(ref, p));
  double ratio = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < a.size(); ++t) ratio = std::min(ratio, a[t] / ref.initial_areas[t]);
  return ratio;
}

double DesignProblem::max_step_keeping_areas(const VecX& p, const VecX& d, double fraction) const {
  const Points2 x = rest_positions(p);
  const Points2 dx = ref_.coordinates.rest_positions(d);  // Xbar is affine in p
  const Triangles& tri = sim_.garment().topology->pattern_triangles;
  auto cross = [](const Eigen::RowVector2d& a, const Eigen::RowVector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  double alpha = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < tri.rows(); ++t) {
    const Eigen::RowVector2d e1 = x.row(tri(t, 1)) - x.row(tri(t, 0));
    const Eigen::RowVector2d e2 = x.row(tri(t, 2)) - x.row(tri(t, 0));
    const Eigen::RowVector2d f1 = dx.row(tri(t, 1)) - dx.row(tri(t, 0));
    const Eigen::RowVector2d f2 = dx.row(tri(t, 2)) - dx.row(tri(t, 0));
    // 2 A(α) = c0 + c1 α + c2 α²; the bound is the first α > 0 with 2 A(α) = fraction · c0.
    const double c0 = cross(e1, e2), c1 = cross(e1, f2) + cross(f1, e2), c2 = cross(f1, f2);
    const double orient = ref_.initial_areas[t] < 0.0 ? -1.0 : 1.0;
    const double a = orient * c2, b = orient * c1, c = orient * (1.0 - fraction) * c0;
    if (!(c > 0.0)) continue;  // an inverted triangle: the evaluation rejects it
    // a α² + b α + c = 0, smallest positive root (c > 0).
    double root = std::numeric_limits<double>::infinity();
    if (std::abs(a) < 1e-300) {
      if (b < 0.0) root = -c / b;
    } else {
      const double disc = b * b - 4.0 * a * c;
      if (disc >= 0.0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        for (double r : {q / a, q != 0.0 ? c / q : -1.0})
          if (r > 0.0) root = std::min(root, r);
      }
    }
    alpha = std::min(alpha, root);
  }
  return alpha;
}

DesignEvaluation DesignProblem::evaluate(const VecX& p, bool with_gradient) {
  const SparseCholesky* held =
      accepted_generation_ == adjoint_.generation() ? adjoint_.held_factorization() : nullptr;
  return evaluate_at(ref_, p, accepted_state_, held, with_gradient);
}

DesignEvaluation DesignProblem::evaluate_at(const Reference& ref, const VecX& p,
                                            const EmbeddedState& start, const SparseCholesky* held,
                                            bool with_gradient) {
  DesignEvaluation ev;
  last_ok_ = false;
  const auto t0 = SteadyClock::now();
  const Points2 rest = rest_positions_at(ref, p);
  if (!p.allFinite()) {
    ev.failure = "the parameters are not finite";
    return ev;
  }
  if (const double ratio = min_area_ratio_at(ref, p); ratio < options_.min_area_ratio) {
    ev.failure = "a pattern triangle " + std::string(ratio <= 0.0 ? "flipped" : "degenerated") +
                 " (area ratio " + std::to_string(ratio) + ")";
    return ev;
  }
  current_p_ = p;
  gradient_generation_ = -1;
  try {
    sim_.set_state(start);
    const Points3 start_positions = sim_.problem().garment_positions();
    sim_.set_rest_positions(rest);
    newton_factorized_ = false;
    ChordSteps chords{held, options_.reuse_factorizations};
    chords.on_factorized = [this] {
      newton_state_ = sim_.problem().state();
      newton_factorized_ = true;
    };
    const NewtonReport report = sim_.solve(chords);
    ev.newton_iterations = report.iterations;
    ev.chord_steps = report.chord_steps;
    ev.force_accepted_steps = report.force_accepted_steps;
    ev.factorizations = report.factorizations;
    for (const NewtonIteration& it : report.history) {
      ev.seconds_assembly += it.seconds_assembly;
      ev.seconds_factorization += it.seconds_factorization;
    }
    ev.force_residual = report.final_force_norm;
    if (!report.converged) {
      ev.failure = "forward solve: " + report.message;
      return ev;
    }
    if (const std::string place = non_finite_place(sim_.problem().state()); !place.empty()) {
      ev.failure = "forward solve: the equilibrium is not finite at " + place;
      return ev;
    }
    record_equilibrium_move(start_positions, ev);
  } catch (const InputError& e) {
    ev.failure = std::string("pattern rejected: ") + e.what();
    return ev;
  } catch (const SolverError& e) {
    ev.failure = std::string("forward solve: ") + e.what();
    return ev;
  }
  ev.seconds_forward = seconds_since(t0);

  const auto t1 = SteadyClock::now();
  const SimulationDesignState ds(sim_);
  try {
    ev.term_values = ref.objective->weighted_values(ds.view());
  } catch (const SolverError& e) {
    ev.failure = std::string("design objective: ") + e.what();
    return ev;
  }
  ev.seconds_objective = seconds_since(t1);
  ev.value = 0.0;
  for (double v : ev.term_values) ev.value += v;
  if (!std::isfinite(ev.value)) {
    ev.failure = "the design objective is not finite";
    return ev;
  }
  ev.ok = true;
  last_ok_ = true;
  if (with_gradient) add_gradient_at(ref, ev);
  return ev;
}

void DesignProblem::record_equilibrium_move(const Points3& accepted_positions,
                                            DesignEvaluation& ev) const {
  const Points3& x = sim_.problem().garment_positions();
  if (x.rows() != accepted_positions.rows() || x.rows() == 0) return;
  Eigen::Index vertex = 0;
  ev.equilibrium_move = (x - accepted_positions).rowwise().norm().maxCoeff(&vertex);
  ev.moved_vertex = static_cast<int>(vertex);
  ev.moved_vertex_position = accepted_positions.row(vertex).transpose();
  ev.moved_vertex_label = sim_.problem().garment_vertex_label(ev.moved_vertex);
}

bool DesignProblem::add_gradient(DesignEvaluation& ev) { return add_gradient_at(ref_, ev); }

bool DesignProblem::add_gradient_at(const Reference& ref, DesignEvaluation& ev) {
  if (!last_ok_ || !ev.ok)
    throw std::logic_error("DesignProblem::add_gradient: no successful evaluation to complete");
  const auto t0 = SteadyClock::now();
  try {
    // The forward solve's last factorization is held from now on (when the adjoint
    // needs one of its own at the equilibrium, that one is). A shifted one is not: it
    // preconditions the next predictor and the adjoint's GMRES poorly.
    const long generation = adjoint_.generation();
    if (newton_factorized_ && sim_.newton().factorization_shift() == 0.0)
      adjoint_.adopt(sim_, newton_state_);
    newton_factorized_ = false;
    const AdjointResult r = adjoint_.rest_gradient(sim_, *ref.objective);
    if (adjoint_.generation() != generation) held_parameters_ = current_p_;
    ev.gradient = ref.coordinates.pull_back(r.rest_gradient);
    ev.hessian_shift = r.hessian_shift;
    ev.adjoint_residual = r.adjoint_residual;
    ev.adjoint_method = r.method;
    ev.krylov_iterations = r.krylov_iterations;
    ev.adjoint_factorizations = r.factorizations;
    if (adjoint_.held_factorization()) gradient_generation_ = adjoint_.generation();
    // Never accepted with a non-finite gradient: it would enter the L-BFGS memory and
    // every later direction.
    if (!ev.gradient.allFinite()) {
      ev.ok = false;
      ev.failure = "adjoint: the design gradient is not finite";
      last_ok_ = false;
    }
  } catch (const SolverError& e) {
    ev.ok = false;
    ev.failure = std::string("adjoint: ") + e.what();
    last_ok_ = false;
  }
  ev.seconds_adjoint = seconds_since(t0);
  return ev.ok;
}

void DesignProblem::accept() {
  if (!last_ok_)
    throw std::logic_error("DesignProblem::accept: the last evaluation did not succeed");
  accepted_p_ = current_p_;
  accepted_state_ = sim_.problem().state();
  accepted_generation_ = gradient_generation_;
  if (accepted_generation_ >= 0 && accepted_generation_ == adjoint_.generation()) {
    accepted_ordering_ = adjoint_.held_ordering();
    accepted_held_ = current_held_point();
  } else {
    accepted_held_.reset();
  }
}

std::optional<HeldFactorizationPoint> DesignProblem::current_held_point() const {
  if (!adjoint_.held_factorization()) return std::nullopt;
  return HeldFactorizationPoint{held_parameters_, adjoint_.held_state(), adjoint_.held_shift()};
}

void DesignProblem::restore_accepted() {
  sim_.set_rest_positions(rest_positions(accepted_p_));
  sim_.set_state(accepted_state_);
  current_p_ = accepted_p_;
  last_ok_ = false;
}

void DesignProblem::set_accepted(const VecX& p, const EmbeddedState& state,
                                 const CholeskyOrdering& held_ordering,
                                 const std::optional<HeldFactorizationPoint>& held_point) {
  if (p.size() != num_parameters())
    throw InputError("checkpoint", "it has " + std::to_string(p.size()) +
                                       " design parameters, the garment needs " +
                                       std::to_string(num_parameters()));
  if (static_cast<int>(state.garment.size()) != sim_.garment().num_garment_vertices() ||
      state.body.rows() != sim_.body().volume.vertices.rows())
    throw InputError("checkpoint", "its state does not match the garment and body");
  if (held_point && (held_point->parameters.size() != p.size() ||
                     held_point->state.garment.size() != state.garment.size() ||
                     held_point->state.body.rows() != state.body.rows()))
    throw InputError("checkpoint", "its held factorization point does not match the design");
  accepted_p_ = p;
  accepted_state_ = state;
  accepted_generation_ = -1;
  accepted_ordering_ = held_ordering;
  accepted_held_.reset();
  adjoint_.set_next_ordering(held_ordering);
  if (held_point) {
    // The factorization the uninterrupted run held here, made again where it was made.
    sim_.set_rest_positions(rest_positions(held_point->parameters));
    sim_.set_state(held_point->state);
    if (adjoint_.factorize_held(sim_, held_point->shift)) {
      held_parameters_ = held_point->parameters;
      accepted_generation_ = adjoint_.generation();
      accepted_held_ = current_held_point();
    }
  }
  restore_accepted();
}

}  // namespace tightfit
