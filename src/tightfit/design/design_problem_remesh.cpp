#include "tightfit/design/optimization_problem.hpp"

#include <cmath>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/finite_state.hpp"
#include "tightfit/garment/pattern_compare.hpp"

/// DesignProblem's remeshing (remesh, degraded_pieces), the restore of a checkpoint's
/// remeshed design and in-memory snapshots of the accepted design.
namespace tightfit {

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

DesignProblem::Snapshot DesignProblem::snapshot() const {
  return Snapshot{sim_.garment(), ref_, remeshed_, accepted_p_, accepted_state_};
}

void DesignProblem::restore(const Snapshot& s) {
  if (s.garment.topology != sim_.garment().topology) sim_.replace_garment(s.garment, s.state);
  ref_ = s.ref;
  remeshed_ = s.remeshed;
  set_accepted(s.parameters, s.state);
}

}  // namespace tightfit
