#include "tightfit/design/optimization_problem.hpp"

#include "tightfit/design/finite_state.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/garment/pattern_record.hpp"

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

std::vector<int> DesignProblem::degraded_pieces() const {
  const PatternRemeshOptions& o = options_.remesh;
  Pattern pattern = sim_.garment().pattern;
  std::vector<int> out;
  const Points2 rest = rest_positions(accepted_p_);
  int row = 0;
  for (size_t k = 0; k < pattern.pieces.size(); ++k) {
    PatternPiece& piece = pattern.pieces[k];
    piece.rest = rest.middleRows(row, piece.rest.rows());
    row += static_cast<int>(piece.rest.rows());
    const PieceQuality q = piece_quality(piece);
    const double h = target_edge_[k];
    const double angle_floor = std::min(o.min_angle_deg, 0.75 * ref_.fresh[k].min_angle_deg);
    const double area_floor =
        std::min(o.min_area_fraction * std::sqrt(3.0) / 4.0 * h * h, 0.75 * ref_.fresh[k].min_area);
    if (q.min_area <= 0.0 || q.min_angle_deg < angle_floor || q.min_area < area_floor)
      out.push_back(static_cast<int>(k));
  }
  return out;
}

RemeshOutcome DesignProblem::remesh(const std::vector<int>& pieces) {
  if (!make_objective_) throw std::logic_error("DesignProblem::remesh: no objective factory");
  const auto t0 = SteadyClock::now();
  RemeshOutcome out;
  restore_accepted();
  const Garment old_garment = sim_.garment();
  const EmbeddedState old_state = accepted_state_;
  const Points3 positions = sim_.garment_positions();
  out.parameters_before = num_parameters();
  out.garment_vertices_before = old_garment.num_garment_vertices();

  PatternRemeshResult r;
  try {
    r = remesh_garment(old_garment, old_state, positions, sim_.surface(), pieces, target_edge_,
                       options_.remesh.smoothing_iterations);
  } catch (const std::exception& e) {  // an input, solver or logic error: nothing applied yet
    out.failure = std::string("remeshing: ") + e.what();
    out.seconds = seconds_since(t0);
    return out;
  }
  // A remeshing never hands on a NaN: that is a solver failure, not a step to undo
  // and retry (nothing has been changed yet).
  if (std::string place = non_finite_place(r.garment.pattern); !place.empty())
    throw SolverError("the remeshed pattern has a non-finite rest position at " + place);
  if (std::string place = non_finite_place(r.state); !place.empty())
    throw SolverError("the remeshed garment's transferred state is not finite at " + place);
  out.pieces = r.remeshed;
  out.min_angle_before = 180.0;
  out.min_angle_after = 180.0;
  std::vector<PieceQuality> fresh = ref_.fresh;
  std::vector<Points2> mesh_rest = ref_.mesh_rest;
  for (int k : r.remeshed) {
    mesh_rest[static_cast<size_t>(k)] = r.garment.pattern.pieces[static_cast<size_t>(k)].rest;
    out.min_angle_before =
        std::min(out.min_angle_before,
                 piece_quality(old_garment.pattern.pieces[static_cast<size_t>(k)]).min_angle_deg);
    fresh[static_cast<size_t>(k)] = piece_quality(r.garment.pattern.pieces[static_cast<size_t>(k)]);
    out.min_angle_after =
        std::min(out.min_angle_after, fresh[static_cast<size_t>(k)].min_angle_deg);
  }

  // The reference is swapped in only when the remeshed problem solved: a failure puts
  // the old garment back at the accepted point, which nothing has changed.
  auto undo = [&](const std::string& why) {
    out.ok = false;
    out.failure = why;
    sim_.replace_garment(old_garment, old_state);
    restore_accepted();
    // The next trials start from the factorization at the accepted point, as a run
    // resumed here would: make it again if the failed re-solve replaced it.
    const long held_generation = accepted_generation_;
    accepted_generation_ = -1;
    if (held_generation >= 0) {
      if (held_generation != adjoint_.generation()) {
        adjoint_.factorize_held(sim_);
        held_parameters_ = accepted_p_;
        accepted_held_ = current_held_point();
      }
      if (adjoint_.held_factorization()) accepted_generation_ = adjoint_.generation();
    }
    out.seconds = seconds_since(t0);
    return out;
  };

  std::optional<Reference> next;
  try {
    sim_.replace_garment(r.garment, r.state);
    BiharmonicCoordinates coordinates(sim_.garment().pattern, ref_.coordinates, r.unchanged);
    auto objective = make_objective_(sim_);
    if (!objective || objective->entries().size() != ref_.objective->entries().size())
      throw std::invalid_argument("the objective factory built other terms after remeshing");
    next = make_reference(std::move(objective), std::move(coordinates), std::move(fresh),
                          std::move(mesh_rest));
  } catch (const std::exception& e) {
    // Whatever failed (a rejected pattern, a solver, an objective factory that built
    // other terms): the problem is put back as it was, never left half-remeshed.
    return undo(std::string("remeshing: ") + e.what());
  }
  const EmbeddedState start = sim_.problem().state();
  out.evaluation = evaluate_at(*next, next->initial_parameters, start, nullptr, true);
  if (!out.evaluation.ok) return undo("re-solve after remeshing: " + out.evaluation.failure);
  ref_ = std::move(*next);
  accept();
  remeshed_ = true;
  out.ok = true;
  out.parameters_after = num_parameters();
  out.garment_vertices_after = sim_.garment().num_garment_vertices();
  out.triangles_after = static_cast<int>(sim_.garment().topology->pattern_triangles.rows());
  out.seconds = seconds_since(t0);
  return out;
}

std::optional<RemeshedDesign> DesignProblem::remeshed_design() const {
  if (!remeshed_) return std::nullopt;
  RemeshedDesign d;
  Garment g = sim_.garment();
  g.set_rest_positions(ref_.initial_rest);
  d.pattern = std::move(g.pattern);
  d.mesh_rest = ref_.mesh_rest;
  return d;
}

void DesignProblem::restore_remeshed_design(const RemeshedDesign& design,
                                            const EmbeddedState& state) {
  if (!make_objective_)
    throw std::logic_error("DesignProblem::restore_remeshed_design: no objective factory");
  const std::string source = "checkpoint";
  const Pattern& scene = sim_.garment().pattern;
  const Pattern& p = design.pattern;
  check_saved_pattern(p, scene, source, "/remeshed/pattern", " (a checkpoint of another garment?)");
  if (design.mesh_rest.size() != p.pieces.size())
    throw InputError(source, "/remeshed/mesh_rest: " + std::to_string(design.mesh_rest.size()) +
                                 " pieces, the pattern has " + std::to_string(p.pieces.size()));
  Pattern mesh_pattern = p;
  std::vector<PieceQuality> fresh;
  for (size_t k = 0; k < p.pieces.size(); ++k) {
    if (design.mesh_rest[k].rows() != p.pieces[k].rest.rows())
      throw InputError(source, "/remeshed/mesh_rest/" + std::to_string(k) + ": " +
                                   std::to_string(design.mesh_rest[k].rows()) +
                                   " positions, the piece has " +
                                   std::to_string(p.pieces[k].rest.rows()) + " vertices");
    mesh_pattern.pieces[k].rest = design.mesh_rest[k];
    fresh.push_back(piece_quality(mesh_pattern.pieces[k]));
  }

  Garment garment;
  BiharmonicCoordinates coordinates = ref_.coordinates;
  try {
    garment = weld_pattern(p);
    coordinates = BiharmonicCoordinates(mesh_pattern);
  } catch (const InputError& e) {
    throw InputError(source, std::string("/remeshed: ") + e.what());
  } catch (const SolverError& e) {
    throw InputError(source, std::string("/remeshed: the biharmonic coordinates of the mesh "
                                         "rest positions failed: ") +
                                 e.what());
  }
  if (static_cast<int>(state.garment.size()) != garment.num_garment_vertices() ||
      state.body.rows() != sim_.body().volume.vertices.rows())
    throw InputError(source, "/state: " + std::to_string(state.garment.size()) +
                                 " garment surface points and " +
                                 std::to_string(state.body.rows()) +
                                 " body positions, the remeshed garment has " +
                                 std::to_string(garment.num_garment_vertices()) + " and the body " +
                                 std::to_string(sim_.body().volume.vertices.rows()));
  // The factory builds the terms from the simulation, so the simulation takes the
  // remeshed garment first; it gets its own back if the factory throws.
  const Garment scene_garment = sim_.garment();
  const EmbeddedState scene_state = sim_.problem().state();
  sim_.replace_garment(std::move(garment), state);
  std::shared_ptr<const DesignTermSum> objective;
  try {
    objective = make_objective_(sim_);
    if (!objective || objective->entries().size() != ref_.objective->entries().size())
      throw std::invalid_argument(
          "the objective factory built other terms for the remeshed pattern");
  } catch (...) {
    sim_.replace_garment(scene_garment, scene_state);
    throw;
  }
  ref_ = make_reference(std::move(objective), std::move(coordinates), std::move(fresh),
                        design.mesh_rest);
  remeshed_ = true;
  accept_reference();
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
