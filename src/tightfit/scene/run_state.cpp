#include "tightfit/scene/run_state.hpp"

#include <cmath>
#include <cstdint>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/garment/pattern_compare.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"
#include "tightfit/scene/pattern_record.hpp"

namespace tightfit {
namespace {

constexpr const char* kFormat = "tightfit-run-state";
constexpr int kVersion = 1;

std::string at(const std::string& path, size_t i) { return path + "/" + std::to_string(i); }

/// Rows of `width` finite numbers at JSON pointer `path`.
Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> read_rows(
    const nlohmann::json& j, int width, const std::string& source, const std::string& path) {
  const std::string what = "expected an array of [" + std::to_string(width) + " numbers]";
  if (!j.is_array()) throw InputError(source, path + ": " + what);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(
      static_cast<Eigen::Index>(j.size()), width);
  for (size_t i = 0; i < j.size(); ++i) {
    const nlohmann::json& row = j[i];
    if (!row.is_array() || row.size() != static_cast<size_t>(width))
      throw InputError(source, at(path, i) + ": expected " + std::to_string(width) + " numbers");
    for (int c = 0; c < width; ++c) {
      if (!row[c].is_number() || !std::isfinite(row[c].get<double>()))
        throw InputError(source, at(at(path, i), c) + ": expected a finite number");
      if (std::abs(row[c].get<double>()) > kMaxCoordinate)
        throw InputError(source, at(at(path, i), c) + ": " + format_number(row[c].get<double>()) +
                                     " m is not a coordinate of a garment or body (more than " +
                                     format_number(kMaxCoordinate) + " m from the origin)");
      m(static_cast<Eigen::Index>(i), c) = row[c].get<double>();
    }
  }
  return m;
}

Triangles read_triangles(const nlohmann::json& j, const std::string& source,
                         const std::string& path) {
  if (!j.is_array()) throw InputError(source, path + ": expected an array of [a, b, c]");
  Triangles t(static_cast<Eigen::Index>(j.size()), 3);
  for (size_t i = 0; i < j.size(); ++i) {
    const nlohmann::json& row = j[i];
    if (!row.is_array() || row.size() != 3)
      throw InputError(source, at(path, i) + ": expected [a, b, c]");
    for (int c = 0; c < 3; ++c) {
      if (!row[c].is_number_integer() || row[c].get<long long>() < 0)
        throw InputError(source, at(at(path, i), c) + ": expected a vertex index >= 0");
      t(static_cast<Eigen::Index>(i), c) = row[c].get<int>();
    }
  }
  return t;
}

nlohmann::json rows_json(const auto& m) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(i, c));
    a.push_back(std::move(row));
  }
  return a;
}

}  // namespace

RunState make_run_state(const std::string& command, const SceneSpec& spec, const Garment& garment,
                        const EmbeddedState& state, const Pattern* scene_pattern) {
  RunState s;
  s.command = command;
  s.scene_file = spec.file;
  s.scene_base_dir = std::filesystem::absolute(spec.base_dir).lexically_normal();
  if (!s.scene_base_dir.has_filename()) s.scene_base_dir = s.scene_base_dir.parent_path();
  s.scene = spec.document;
  for (const PatternPiece& p : garment.pattern.pieces)
    s.pieces.push_back({p.name, p.rest, p.triangles});
  if (scene_pattern && !same_pattern_meshes(garment.pattern, *scene_pattern))
    s.pattern = garment.pattern;
  s.state = state;
  s.result = nlohmann::json::object();
  return s;
}

nlohmann::json history_json(const std::vector<OptimizationIteration>& history,
                            const std::vector<std::string>& term_names) {
  nlohmann::json its = nlohmann::json::array();
  for (const OptimizationIteration& it : history) its.push_back(iteration_json(it, term_names));
  return {{"terms", term_names}, {"iterations", its}};
}

nlohmann::json run_state_json(const RunState& s) {
  nlohmann::json pattern;
  if (s.pattern) {
    pattern = pattern_record_json(*s.pattern);
    pattern["remeshed"] = true;
  } else {
    nlohmann::json pieces = nlohmann::json::array();
    for (const RunStatePiece& p : s.pieces)
      pieces.push_back(
          {{"name", p.name}, {"rest", rows_json(p.rest)}, {"triangles", rows_json(p.triangles)}});
    pattern = {{"pieces", pieces}};
  }
  nlohmann::json garment = nlohmann::json::array();
  for (const SurfacePoint& q : s.state.garment) garment.push_back({q.face, q.u, q.v});
  nlohmann::json j = {{"format", kFormat},
                      {"version", kVersion},
                      {"command", s.command},
                      {"scene_file", s.scene_file},
                      {"scene_base_dir", s.scene_base_dir.string()},
                      {"scene", s.scene},
                      {"pattern", pattern},
                      {"garment", garment},
                      {"body", rows_json(s.state.body)},
                      {"result", s.result}};
  if (s.command == "optimize") j["history"] = history_json(s.history, s.term_names);
  if (s.initial_garment)
    j["initial_garment"] = {{"vertices", rows_json(s.initial_garment->vertices)},
                            {"triangles", rows_json(s.initial_garment->faces)}};
  return j;
}

RunState run_state_from_json(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "expected a JSON object (a tightfit run state)");
  RunState s;
  JsonFields f(j, source, "");
  if (f.string("format") != kFormat) f.fail("not a tightfit run state", "format");
  if (f.integer("version") != kVersion)
    f.fail("unsupported version (this tightfit reads version " + std::to_string(kVersion) + ")",
           "version");
  s.command = f.choice("command", {"simulate", "layout", "optimize"});
  s.scene_file = f.string("scene_file");
  s.scene_base_dir = f.string("scene_base_dir");
  if (!s.scene_base_dir.is_absolute()) f.fail("expected an absolute folder", "scene_base_dir");
  s.scene = f.raw("scene");
  if (!s.scene.is_object()) f.fail("expected the scene document (an object)", "scene");

  const nlohmann::json& pattern_json = f.raw("pattern");
  if (!pattern_json.is_object()) f.fail("expected an object (the pattern)", "pattern");
  if (pattern_json.contains("remeshed")) {
    if (pattern_json["remeshed"] != true)
      throw InputError(source, "/pattern/remeshed: expected true (or no such member)");
    nlohmann::json record = pattern_json;
    record.erase("remeshed");
    s.pattern = pattern_record_from_json(record, source, "/pattern");
    for (const PatternPiece& p : s.pattern->pieces)
      s.pieces.push_back({p.name, p.rest, p.triangles});
  } else {
    JsonFields pattern(pattern_json, source, "/pattern");
    for (JsonFields& p : pattern.objects("pieces", true)) {
      RunStatePiece piece;
      piece.name = p.string("name");
      piece.rest = read_rows(p.raw("rest"), 2, source, p.child_path("rest"));
      piece.triangles = read_triangles(p.raw("triangles"), source, p.child_path("triangles"));
      p.finish();
      s.pieces.push_back(std::move(piece));
    }
    pattern.finish();
  }

  const nlohmann::json& garment = f.raw("garment");
  if (!garment.is_array()) f.fail("expected an array of [face, u, v]", "garment");
  for (size_t i = 0; i < garment.size(); ++i) {
    const nlohmann::json& e = garment[i];
    if (!e.is_array() || e.size() != 3 || !e[0].is_number_integer() || !e[1].is_number() ||
        !e[2].is_number() || !std::isfinite(e[1].get<double>()) ||
        !std::isfinite(e[2].get<double>()))
      throw InputError(source, at("/garment", i) + ": expected [face, u, v]");
    if (e[0].get<std::int64_t>() < 0 || e[0].get<std::int64_t>() > (std::int64_t{1} << 30) ||
        std::abs(e[1].get<double>()) > kMaxCoordinate ||
        std::abs(e[2].get<double>()) > kMaxCoordinate)
      throw InputError(source, at("/garment", i) + ": " + e.dump() +
                                   " is not a point on a triangle (face index or coordinates "
                                   "out of range)");
    s.state.garment.push_back({e[0].get<int>(), e[1].get<double>(), e[2].get<double>()});
  }
  s.state.body = read_rows(f.raw("body"), 3, source, "/body");

  if (s.command == "optimize") {
    auto history = f.object("history", true);
    const nlohmann::json& names = history->raw("terms");
    if (!names.is_array()) history->fail("expected an array of term names", "terms");
    for (size_t k = 0; k < names.size(); ++k) {
      if (!names[k].is_string())
        throw InputError(source, at("/history/terms", k) + ": expected a string");
      s.term_names.push_back(names[k].get<std::string>());
    }
    const nlohmann::json& its = history->raw("iterations");
    if (!its.is_array() || its.empty())
      history->fail("expected a non-empty array of iteration records", "iterations");
    for (size_t i = 0; i < its.size(); ++i)
      s.history.push_back(
          iteration_from_json(its[i], s.term_names, source, at("/history/iterations", i)));
    history->finish();
  }
  s.result = f.raw("result");
  if (!s.result.is_object()) f.fail("expected an object (the run's summary)", "result");
  if (auto initial = f.object("initial_garment")) {
    TriMesh mesh;
    mesh.vertices = read_rows(initial->raw("vertices"), 3, source, "/initial_garment/vertices");
    mesh.faces = read_triangles(initial->raw("triangles"), source, "/initial_garment/triangles");
    if (mesh.faces.size() > 0 &&
        (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertices.rows()))
      initial->fail("a triangle names a vertex that does not exist", "triangles");
    initial->finish();
    s.initial_garment = std::move(mesh);
  }
  f.finish();
  return s;
}

void write_run_state(const std::filesystem::path& file, const RunState& state) {
  write_json_atomically(file, run_state_json(state));
}

RunState read_run_state(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(file.string(),
                     "no saved run state (expected the state.json that "
                     "`tightfit simulate`, `layout` or `optimize` write)");
  return run_state_from_json(read_json_file(file.string()), file.string());
}

SceneSpec run_state_scene(const RunState& state, const std::string& source) {
  try {
    return parse_scene(state.scene, state.scene_file, state.scene_base_dir);
  } catch (const InputError& e) {
    throw InputError(source, std::string("/scene: ") + e.what());
  }
}

namespace {

const char* const kChanged = " (the scene or its files changed since the run?)";

/// The saved pieces against the scene's (names, vertex counts, triangles).
void check_scene_pieces(const RunState& s, const Garment& garment, const std::string& source) {
  const auto& pieces = garment.pattern.pieces;
  if (s.pieces.size() != pieces.size())
    throw InputError(source, "/pattern/pieces: " + std::to_string(s.pieces.size()) +
                                 " pieces, the scene's garment has " +
                                 std::to_string(pieces.size()) + kChanged);
  for (size_t k = 0; k < pieces.size(); ++k) {
    const std::string path = at("/pattern/pieces", k);
    const RunStatePiece& p = s.pieces[k];
    if (p.name != pieces[k].name)
      throw InputError(source, path + "/name: \"" + p.name + "\", the scene's piece is \"" +
                                   pieces[k].name + "\"" + kChanged);
    if (p.rest.rows() != pieces[k].rest.rows())
      throw InputError(source, path + "/rest: " + std::to_string(p.rest.rows()) +
                                   " vertices, the scene's piece has " +
                                   std::to_string(pieces[k].rest.rows()) + kChanged);
    if (p.triangles != pieces[k].triangles)
      throw InputError(source, path + "/triangles: differ from the scene's piece mesh" + kChanged);
  }
}

}  // namespace

Garment run_state_garment(const RunState& s, const Garment& scene_garment, const Body& body,
                          int num_surface_faces, const std::string& source) {
  Garment garment;
  if (s.pattern) {
    check_saved_pattern(*s.pattern, scene_garment.pattern, source, "/pattern", kChanged);
    try {
      garment = weld_pattern(*s.pattern);
    } catch (const InputError& e) {
      throw InputError(source, std::string("/pattern: ") + e.what());
    }
  } else {
    check_scene_pieces(s, scene_garment, source);
    garment = scene_garment;
    garment.set_rest_positions(stacked_rest_positions(s));
  }
  if (static_cast<int>(s.state.garment.size()) != garment.num_garment_vertices())
    throw InputError(
        source, "/garment: " + std::to_string(s.state.garment.size()) + " surface points, the " +
                    (s.pattern ? "saved pattern's" : "scene's") + " garment has " +
                    std::to_string(garment.num_garment_vertices()) + " vertices" + kChanged);
  check_surface_points(s.state.garment, num_surface_faces, source, "/garment");
  if (s.state.body.rows() != body.num_vertices())
    throw InputError(source, "/body: " + std::to_string(s.state.body.rows()) +
                                 " positions, the scene's body has " +
                                 std::to_string(body.num_vertices()) + " vertices" + kChanged);
  garment.embedding = s.state.garment;
  return garment;
}

Points2 stacked_rest_positions(const RunState& state) {
  Eigen::Index n = 0;
  for (const RunStatePiece& p : state.pieces) n += p.rest.rows();
  Points2 rest(n, 2);
  Eigen::Index row = 0;
  for (const RunStatePiece& p : state.pieces) {
    rest.middleRows(row, p.rest.rows()) = p.rest;
    row += p.rest.rows();
  }
  return rest;
}

}  // namespace tightfit
