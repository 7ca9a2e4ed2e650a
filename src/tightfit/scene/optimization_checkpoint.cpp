#include "tightfit/scene/optimization_checkpoint.hpp"

#include <algorithm>
#include <cmath>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/scene/pattern_record.hpp"

namespace tightfit {
namespace {

constexpr const char* kFormat = "tightfit-optimization-checkpoint";
constexpr int kVersion = 1;

nlohmann::json vector_json(const VecX& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

/// A flat array of finite numbers at `path` (`length` entries when >= 0).
VecX read_vector(const nlohmann::json& j, const std::string& source, const std::string& path,
                 Eigen::Index length = -1) {
  if (!j.is_array()) throw InputError(source, path + ": expected an array of numbers");
  if (length >= 0 && static_cast<Eigen::Index>(j.size()) != length)
    throw InputError(source, path + ": expected " + std::to_string(length) + " numbers, got " +
                                 std::to_string(j.size()));
  VecX v(j.size());
  for (size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>()))
      throw InputError(source, path + "/" + std::to_string(i) + ": expected a finite number");
    v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
  }
  return v;
}

/// An array of arrays of numbers (each `width` long when >= 0).
std::vector<VecX> read_vectors(const nlohmann::json& j, const std::string& source,
                               const std::string& path, Eigen::Index width = -1) {
  if (!j.is_array()) throw InputError(source, path + ": expected an array of arrays");
  std::vector<VecX> out;
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(read_vector(j[i], source, path + "/" + std::to_string(i), width));
  return out;
}

nlohmann::json state_json(const EmbeddedState& state) {
  nlohmann::json garment = nlohmann::json::array();
  for (const SurfacePoint& s : state.garment) garment.push_back({s.face, s.u, s.v});
  nlohmann::json body = nlohmann::json::array();
  for (Eigen::Index i = 0; i < state.body.rows(); ++i)
    body.push_back({state.body(i, 0), state.body(i, 1), state.body(i, 2)});
  return {{"garment", garment}, {"body", body}};
}

/// The state object read by `fields` (at `path`, e.g. "/state").
EmbeddedState read_state(JsonFields& fields, const std::string& source, const std::string& path) {
  EmbeddedState state;
  const nlohmann::json& garment = fields.raw("garment");
  if (!garment.is_array()) fields.fail("expected an array of [face, u, v]", "garment");
  for (size_t i = 0; i < garment.size(); ++i) {
    const nlohmann::json& e = garment[i];
    if (!e.is_array() || e.size() != 3 || !e[0].is_number_integer() || !e[1].is_number() ||
        !e[2].is_number())
      throw InputError(source, path + "/garment/" + std::to_string(i) + ": expected [face, u, v]");
    state.garment.push_back({e[0].get<int>(), e[1].get<double>(), e[2].get<double>()});
  }
  const std::vector<VecX> body = read_vectors(fields.raw("body"), source, path + "/body", 3);
  state.body.resize(static_cast<Eigen::Index>(body.size()), 3);
  for (size_t i = 0; i < body.size(); ++i)
    state.body.row(static_cast<Eigen::Index>(i)) = body[i].transpose();
  fields.finish();
  return state;
}

nlohmann::json terms_json(const std::vector<double>& values,
                          const std::vector<std::string>& term_names) {
  nlohmann::json terms = nlohmann::json::object();
  for (size_t k = 0; k < term_names.size() && k < values.size(); ++k)
    terms[term_names[k]] = values[k];
  return terms;
}

nlohmann::json remesh_json(const RemeshRecord& r, const std::vector<std::string>& term_names) {
  nlohmann::json j = {{"pieces", r.pieces},
                      {"objective", r.value},
                      {"terms", terms_json(r.term_values, term_names)},
                      {"gradient_norm", r.gradient_norm},
                      {"parameters", r.parameters},
                      {"garment_vertices", r.garment_vertices},
                      {"min_angle_before_deg", r.min_angle_before},
                      {"min_angle_after_deg", r.min_angle_after},
                      {"newton_iterations", r.newton_iterations},
                      {"seconds", r.seconds}};
  if (!r.failure.empty()) j["failure"] = r.failure;
  return j;
}

RemeshRecord remesh_from_json(JsonFields f, const std::vector<std::string>& term_names) {
  RemeshRecord r;
  const nlohmann::json& pieces = f.raw("pieces");
  if (!pieces.is_array()) f.fail("expected an array of piece names", "pieces");
  for (const nlohmann::json& name : pieces) {
    if (!name.is_string()) f.fail("expected an array of piece names", "pieces");
    r.pieces.push_back(name.get<std::string>());
  }
  r.value = f.number("objective");
  auto terms = f.object("terms", true);
  for (const std::string& name : term_names) r.term_values.push_back(terms->number(name));
  terms->finish();
  r.gradient_norm = f.number("gradient_norm");
  r.parameters = f.integer("parameters");
  r.garment_vertices = f.integer("garment_vertices");
  r.min_angle_before = f.number("min_angle_before_deg");
  r.min_angle_after = f.number("min_angle_after_deg");
  r.newton_iterations = f.integer("newton_iterations");
  r.seconds = f.number("seconds");
  r.failure = f.string("failure", "");
  f.finish();
  return r;
}

nlohmann::json snap_json(const SnapRecord& s) {
  return {{"trials", s.trials}, {"rise", s.rise},
          {"step", s.step},     {"move", s.move},
          {"vertex", s.vertex}, {"position", {s.position.x(), s.position.y(), s.position.z()}},
          {"label", s.label}};
}

SnapRecord snap_from_json(JsonFields f) {
  SnapRecord s;
  s.trials = f.integer("trials");
  if (s.trials < 1) f.fail("must be >= 1", "trials");
  s.rise = f.number("rise");
  s.step = f.number("step");
  s.move = f.number("move");
  s.vertex = f.integer("vertex");
  s.position = f.vec3("position");
  s.label = f.string("label", "");
  f.finish();
  return s;
}

}  // namespace

nlohmann::json iteration_json(const OptimizationIteration& it,
                              const std::vector<std::string>& term_names) {
  const nlohmann::json terms = terms_json(it.term_values, term_names);
  nlohmann::json j = {{"iteration", it.iteration},
                      {"objective", it.value},
                      {"terms", terms},
                      {"gradient_norm", it.gradient_norm},
                      {"step_norm", it.step_norm},
                      {"max_point_move", it.max_point_move},
                      {"max_solved_move", it.max_solved_move},
                      {"step_factor", it.step_factor},
                      {"line_search_trials", it.line_search_trials},
                      {"failed_solves", it.failed_solves},
                      {"newton_iterations", it.newton_iterations},
                      {"chord_steps", it.chord_steps},
                      {"force_accepted_steps", it.force_accepted_steps},
                      {"factorizations", it.factorizations},
                      {"adjoint_method", it.adjoint_method},
                      {"krylov_iterations", it.krylov_iterations},
                      {"hessian_shift", it.hessian_shift},
                      {"seconds", it.seconds},
                      {"seconds_forward", it.seconds_forward},
                      {"seconds_objective", it.seconds_objective},
                      {"seconds_adjoint", it.seconds_adjoint},
                      {"seconds_assembly", it.seconds_assembly},
                      {"seconds_factorization", it.seconds_factorization}};
  if (it.remesh) j["remesh"] = remesh_json(*it.remesh, term_names);
  if (it.snap) j["snap"] = snap_json(*it.snap);
  if (it.jump) j["jump"] = true;
  return j;
}

OptimizationIteration iteration_from_json(const nlohmann::json& j,
                                          const std::vector<std::string>& term_names,
                                          const std::string& source, const std::string& path) {
  OptimizationIteration it;
  JsonFields f(j, source, path);
  it.iteration = f.integer("iteration");
  it.value = f.number("objective");
  auto terms = f.object("terms", true);
  for (const std::string& name : term_names) it.term_values.push_back(terms->number(name));
  terms->finish();
  it.gradient_norm = f.number("gradient_norm");
  it.step_norm = f.number("step_norm");
  it.max_point_move = f.number("max_point_move");
  // Records written before the field existed: the accepted move was the reference.
  it.max_solved_move = f.number("max_solved_move", it.max_point_move);
  it.step_factor = f.number("step_factor");
  it.line_search_trials = f.integer("line_search_trials");
  it.failed_solves = f.integer("failed_solves");
  it.newton_iterations = f.integer("newton_iterations");
  it.chord_steps = f.integer("chord_steps", 0);
  it.force_accepted_steps = f.integer("force_accepted_steps", 0);
  it.factorizations = f.integer("factorizations", 0);
  it.adjoint_method = f.string("adjoint_method", std::string());
  it.krylov_iterations = f.integer("krylov_iterations", 0);
  it.hessian_shift = f.number("hessian_shift");
  it.seconds = f.number("seconds");
  it.seconds_forward = f.number("seconds_forward", 0.0);
  it.seconds_objective = f.number("seconds_objective", 0.0);
  it.seconds_adjoint = f.number("seconds_adjoint", 0.0);
  it.seconds_assembly = f.number("seconds_assembly", 0.0);
  it.seconds_factorization = f.number("seconds_factorization", 0.0);
  if (auto r = f.object("remesh")) it.remesh = remesh_from_json(*r, term_names);
  if (auto s = f.object("snap")) it.snap = snap_from_json(*s);
  it.jump = f.boolean("jump", false);
  f.finish();
  return it;
}

nlohmann::json checkpoint_json(const OptimizationCheckpoint& c,
                               const std::vector<std::string>& term_names) {
  nlohmann::json s = nlohmann::json::array(), y = nlohmann::json::array();
  for (const VecX& v : c.memory.s) s.push_back(vector_json(v));
  for (const VecX& v : c.memory.y) y.push_back(vector_json(v));
  nlohmann::json history = nlohmann::json::array();
  for (const OptimizationIteration& it : c.history)
    history.push_back(iteration_json(it, term_names));
  nlohmann::json j = {{"format", kFormat},
                      {"version", kVersion},
                      {"iteration", c.iteration},
                      {"terms", term_names},
                      {"parameters", vector_json(c.parameters)},
                      {"state", state_json(c.state)},
                      {"memory", {{"s", s}, {"y", y}}},
                      {"history", history}};
  if (!c.held_ordering.permutation.empty())
    j["held_ordering"] = {{"permutation", c.held_ordering.permutation},
                          {"factor_nonzeros", c.held_ordering.factor_nonzeros}};
  if (c.held_point)
    j["held_point"] = {{"parameters", vector_json(c.held_point->parameters)},
                       {"state", state_json(c.held_point->state)},
                       {"shift", c.held_point->shift}};
  if (c.remeshed) {
    nlohmann::json mesh_rest = nlohmann::json::array();
    for (const Points2& rest : c.remeshed->mesh_rest) {
      nlohmann::json rows = nlohmann::json::array();
      for (Eigen::Index i = 0; i < rest.rows(); ++i) rows.push_back({rest(i, 0), rest(i, 1)});
      mesh_rest.push_back(std::move(rows));
    }
    j["remeshed"] = {{"pattern", pattern_record_json(c.remeshed->pattern)},
                     {"mesh_rest", mesh_rest}};
  }
  return j;
}

OptimizationCheckpoint checkpoint_from_json(const nlohmann::json& j,
                                            const std::vector<std::string>& term_names,
                                            const std::string& source) {
  OptimizationCheckpoint c;
  JsonFields f(j, source, "");
  if (f.string("format") != kFormat) f.fail("not a tightfit optimization checkpoint", "format");
  if (f.integer("version") != kVersion)
    f.fail("unsupported version (expected " + std::to_string(kVersion) + ")", "version");
  c.iteration = f.integer("iteration");
  if (c.iteration < 0) f.fail("must be >= 0", "iteration");
  f.raw("inputs");  // what the run read (optional): `tightfit optimize --resume` checks it
  const nlohmann::json& names = f.raw("terms");
  if (names != nlohmann::json(term_names))
    f.fail("the checkpoint was written for the objective terms " + names.dump() +
               ", the scene has " + nlohmann::json(term_names).dump(),
           "terms");
  c.parameters = read_vector(f.raw("parameters"), source, "/parameters");

  auto state = f.object("state", true);
  c.state = read_state(*state, source, "/state");

  auto memory = f.object("memory", true);
  c.memory.s = read_vectors(memory->raw("s"), source, "/memory/s", c.parameters.size());
  c.memory.y = read_vectors(memory->raw("y"), source, "/memory/y", c.parameters.size());
  if (c.memory.s.size() != c.memory.y.size()) memory->fail("s and y differ in length");
  memory->finish();

  if (auto ordering = f.object("held_ordering")) {
    const nlohmann::json& perm = ordering->raw("permutation");
    if (!perm.is_array() || perm.empty())
      ordering->fail("expected a non-empty array of indices", "permutation");
    std::vector<char> seen(perm.size(), 0);
    for (size_t i = 0; i < perm.size(); ++i) {
      const nlohmann::json& e = perm[i];
      if (!e.is_number_integer() || e.get<std::int64_t>() < 0 ||
          e.get<std::int64_t>() >= static_cast<std::int64_t>(perm.size()) || seen[e.get<size_t>()])
        throw InputError(source, "/held_ordering/permutation/" + std::to_string(i) +
                                     ": not a permutation of 0 … " +
                                     std::to_string(perm.size() - 1));
      seen[e.get<size_t>()] = 1;
      c.held_ordering.permutation.push_back(e.get<int>());
    }
    c.held_ordering.factor_nonzeros = ordering->positive("factor_nonzeros");
    ordering->finish();
  }
  if (auto held = f.object("held_point")) {
    HeldFactorizationPoint h;
    h.parameters =
        read_vector(held->raw("parameters"), source, "/held_point/parameters", c.parameters.size());
    auto held_state = held->object("state", true);
    h.state = read_state(*held_state, source, "/held_point/state");
    h.shift = held->number("shift");
    if (!std::isfinite(h.shift) || h.shift < 0.0)
      held->fail("expected a finite shift >= 0", "shift");
    held->finish();
    c.held_point = std::move(h);
  }
  if (auto remeshed = f.object("remeshed")) {
    RemeshedDesign d;
    d.pattern = pattern_record_from_json(remeshed->raw("pattern"), source, "/remeshed/pattern");
    const nlohmann::json& mesh_rest = remeshed->raw("mesh_rest");
    if (!mesh_rest.is_array() || mesh_rest.size() != d.pattern.pieces.size())
      remeshed->fail("expected one array of rest positions per piece (" +
                         std::to_string(d.pattern.pieces.size()) + ")",
                     "mesh_rest");
    for (size_t k = 0; k < mesh_rest.size(); ++k) {
      const std::string p = "/remeshed/mesh_rest/" + std::to_string(k);
      const Eigen::Index n = d.pattern.pieces[k].rest.rows();
      const std::vector<VecX> rows = read_vectors(mesh_rest[k], source, p, 2);
      if (static_cast<Eigen::Index>(rows.size()) != n)
        throw InputError(source, p + ": " + std::to_string(rows.size()) +
                                     " positions, the piece has " + std::to_string(n) +
                                     " vertices");
      Points2 rest(n, 2);
      for (Eigen::Index i = 0; i < n; ++i) rest.row(i) = rows[static_cast<size_t>(i)].transpose();
      d.mesh_rest.push_back(std::move(rest));
    }
    remeshed->finish();
    c.remeshed = std::move(d);
  }

  const nlohmann::json& history = f.raw("history");
  if (!history.is_array() || history.empty())
    f.fail("expected a non-empty array of iteration records", "history");
  for (size_t i = 0; i < history.size(); ++i)
    c.history.push_back(
        iteration_from_json(history[i], term_names, source, "/history/" + std::to_string(i)));
  f.finish();
  return c;
}

void write_checkpoint(const std::filesystem::path& file, const OptimizationCheckpoint& c,
                      const std::vector<std::string>& term_names) {
  write_json_atomically(file, checkpoint_json(c, term_names));
}

OptimizationCheckpoint read_checkpoint(const std::filesystem::path& file,
                                       const std::vector<std::string>& term_names) {
  return checkpoint_from_json(read_json_file(file.string()), term_names, file.string());
}

}  // namespace tightfit
