#include "tightfit/solve/garment_simulation.hpp"

#include <algorithm>
#include <numeric>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"
#include "tightfit/subdiv/limit_projector.hpp"

namespace tightfit {
namespace {

double mean_rest_edge_length(const Triangles& triangles, const Points2& rest) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      sum += (rest.row(triangles(t, c)) - rest.row(triangles(t, (c + 1) % 3))).norm();
  return triangles.rows() > 0 ? sum / (3.0 * static_cast<double>(triangles.rows())) : 1.0;
}

}  // namespace

GarmentSimulation::GarmentSimulation(const Body& body, const LimitSurface& surface, Garment garment,
                                     SimulationMaterials materials, NewtonOptions newton)
    : body_(body), surface_(surface), materials_(materials), newton_(newton) {
  if (static_cast<int>(garment.embedding.size()) != garment.num_garment_vertices())
    throw InputError("garment", "the garment is not embedded on the body");
  if (surface_.num_control_vertices() != body_.num_surface_vertices())
    throw InputError("body", "the limit surface does not belong to the body surface");
  adopt_garment(std::move(garment));
  body_energy_ =
      std::make_unique<NeoHookeanEnergy>(body_.volume.vertices, body_.volume.tets, materials_.body);
  EmbeddedState state;
  state.garment = garment_.embedding;
  state.body = body_.volume.vertices;
  rebuild_problem(state);
}

GarmentSimulation::~GarmentSimulation() = default;

void GarmentSimulation::adopt_garment(Garment garment) {
  auto rest = std::make_unique<Points2>(garment.rest_positions());
  auto energies = std::make_unique<GarmentEnergies>(garment.topology, *rest, materials_.fabric,
                                                    materials_.seam);
  force_scale_ = FabricLaw(materials_.fabric).reference_stiffness() *
                 mean_rest_edge_length(garment.topology->pattern_triangles, *rest);
  garment_ = std::move(garment);
  rest_ = std::move(rest);
  energies_ = std::move(energies);
}

void GarmentSimulation::replace_garment(Garment garment, const EmbeddedState& state) {
  if (static_cast<int>(state.garment.size()) != garment.num_garment_vertices() ||
      state.body.rows() != body_.volume.vertices.rows())
    throw InputError("garment", "the replacement state does not match the garment and body");
  garment.embedding = state.garment;
  adopt_garment(std::move(garment));
  rebuild_problem(state);
}

std::string GarmentSimulation::garment_vertex_piece(int vertex) const {
  std::vector<std::string> names;
  for (int p = 0; p < garment_.num_pattern_vertices(); ++p) {
    if (garment_.topology->pattern_to_garment[static_cast<size_t>(p)] != vertex) continue;
    const int piece = garment_.topology->piece_of(p);
    const std::string& name = garment_.pattern.pieces[static_cast<size_t>(piece)].name;
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  if (names.empty()) return {};
  std::string out = names.size() == 1 ? "piece " : "pieces ";
  for (size_t k = 0; k < names.size(); ++k) out += (k ? ", '" : "'") + names[k] + "'";
  return out;
}

EmbeddedSystemSetup GarmentSimulation::problem_setup(bool still_body) {
  EmbeddedSystemSetup setup;
  setup.surface = &surface_;
  for (const RestDependentEnergy* e : rest_dependent_energies())
    setup.garment_energies.push_back(e);
  setup.body_energies.push_back(body_energy_.get());
  if (materials_.rigid_body || still_body) {
    setup.pinned_body.resize(body_.num_vertices());
    std::iota(setup.pinned_body.begin(), setup.pinned_body.end(), 0);
  } else {
    setup.pinned_body = body_.pinned;
  }
  setup.pinned_garment = garment_.topology->pinned;
  setup.force_scale = force_scale_;
  setup.garment_vertex_label = [this](int vertex) { return garment_vertex_piece(vertex); };
  setup.hessian_layouts = hessian_layouts_;
  return setup;
}

void GarmentSimulation::rebuild_problem(const EmbeddedState& state) {
  problem_ = std::make_unique<EmbeddedEquilibrium>(problem_setup(false), state);
}

NewtonReport GarmentSimulation::relax_garment_on_still_body() {
  EmbeddedEquilibrium still(problem_setup(true), problem_->state());
  NewtonOptions options = newton_.options();
  options.relative_force_tolerance =
      std::max(options.relative_force_tolerance, kGarmentFirstTolerance);
  options.max_iterations = std::min(options.max_iterations, kGarmentFirstIterations);
  options.throw_on_failure = false;
  if (const auto report_step = newton_.options().on_step)
    options.on_step = [report_step](const NewtonIteration& it, double seconds) {
      NewtonIteration held = it;
      held.body_held = true;
      report_step(held, seconds);
    };
  NewtonSolver solver(options);
  NewtonReport report = solver.solve(still, {nullptr, true});
  for (NewtonIteration& it : report.history) it.body_held = true;
  report.garment_first_iterations = report.iterations;
  if (report.iterations > 0) set_state(still.state());
  return report;
}

namespace {

// Adds a stage that ran before `report`'s solve: its counts, and its steps in front.
void prepend_stage(NewtonReport& report, const NewtonReport& stage) {
  report.iterations += stage.iterations;
  report.chord_steps += stage.chord_steps;
  report.factorizations += stage.factorizations;
  report.krylov_iterations += stage.krylov_iterations;
  report.force_accepted_steps += stage.force_accepted_steps;
  report.garment_first_iterations += stage.garment_first_iterations;
  report.seconds_total += stage.seconds_total;
  report.history.insert(report.history.begin(), stage.history.begin(), stage.history.end());
}

}  // namespace

NewtonReport GarmentSimulation::relax_garment_stage() {
  try {
    return relax_garment_on_still_body();
  } catch (const SolverError&) {
    return NewtonReport{};  // the coupled solve starts from the state as it was
  }
}

NewtonReport GarmentSimulation::solve(ChordSteps chords) {
  std::vector<NewtonReport> stages;  // before the final coupled solve, in order
  if (garment_first_ && !materials_.rigid_body) {
    if (chords.held) {
      ChordSteps predictor = chords;
      predictor.stop_after_poor_predictor = true;
      NewtonReport predicted = newton_.solve(*problem_, predictor);
      if (!predicted.stopped_after_predictor) {
        garment_.embedding = problem_->state().garment;
        return predicted;
      }
      stages.push_back(std::move(predicted));
    }
    stages.push_back(relax_garment_stage());
  }
  NewtonReport report = newton_.solve(*problem_, chords);
  garment_.embedding = problem_->state().garment;
  for (auto stage = stages.rbegin(); stage != stages.rend(); ++stage) prepend_stage(report, *stage);
  return report;
}

void GarmentSimulation::set_rest_positions(const Points2& rest) {
  energies_->check_rest(rest);
  *rest_ = rest;
  garment_.set_rest_positions(*rest_);
  rebuild_problem(problem_->state());
}

void GarmentSimulation::set_state(const EmbeddedState& state) {
  garment_.embedding = state.garment;
  rebuild_problem(state);
}

FitAnalysis GarmentSimulation::analyze() const {
  FitAnalysis fit;
  const Points3& x = problem_->garment_positions();
  const VecX xf = Eigen::Map<const VecX>(x.data(), x.size());
  fit.elements = analyze_cloth(energies_->cloth(), xf);
  const Triangles faces = garment_.topology->garment_triangles;

  fit.pressure_mid_edge = young_laplace_pressure(fit.elements, mid_edge_shape_operators(x, faces));

  // Exact curvature of the limit surface at the point closest to each element's
  // centroid, where its tangent plane is parallel to the element (a chord). The limit
  // surface reports S = −dn; the pressure uses Λ = dn (positive on convex bodies).
  const int ng = garment_.num_garment_vertices();
  const Points3 control = body_positions().topRows(surface_.num_control_vertices());
  const auto& embedding = problem_->state().garment;
  std::vector<Mat3> element_lambda(faces.rows());
  for (Eigen::Index t = 0; t < faces.rows(); ++t) {
    const Vec3 centroid =
        (x.row(faces(t, 0)) + x.row(faces(t, 1)) + x.row(faces(t, 2))).transpose() / 3.0;
    const SurfacePoint at =
        refine_closest_point(surface_, control, centroid, embedding[faces(t, 0)]);
    const LimitCurvature k = surface_.curvature(at, control);
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = k.e1;
    E.col(1) = k.e2;
    element_lambda[t] = -E * k.shape_operator * E.transpose();
  }
  fit.vertex_normal.resize(ng, 3);
  for (int i = 0; i < ng; ++i) fit.vertex_normal.row(i) = problem_->garment_normal(i).transpose();
  fit.pressure_limit = young_laplace_pressure(fit.elements, element_lambda);

  // Forces on the body: the cloth pulls its vertices with −dU/dx; at equilibrium the
  // body supplies the opposite, so the cloth pushes the body with +dU/dx.
  const VecX gx = problem_->garment_energy_gradient();
  fit.vertex_pressure = vertex_area_pressure(x, faces, gx);
  fit.vertex_force.resize(ng, 3);
  fit.vertex_normal_force.resize(ng);
  for (int i = 0; i < ng; ++i) {
    fit.vertex_force.row(i) = gx.segment<3>(3 * i).transpose();
    fit.vertex_normal_force[i] = gx.segment<3>(3 * i).dot(fit.vertex_normal.row(i).transpose());
  }
  return fit;
}

}  // namespace tightfit
