#include "tightfit/scene/run_state.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "tightfit/common/error.hpp"

namespace tightfit::run_state_test {

namespace fs = std::filesystem;

/// Doubles that a fixed number of printed digits would not give back exactly.
const double kAwkward[] = {0.1,
                           1.0 / 3.0,
                           -2.0 / 7.0,
                           1e-300,
                           5e-324,
                           std::nextafter(1000.0, 0.0),
                           0.30000000000000004,
                           std::nextafter(1.0, 2.0)};

RunState sample_state(const std::string& command) {
  RunState s;
  s.command = command;
  s.scene_file = "examples/scene.json";
  s.scene_base_dir = "/tmp/scenes";
  s.scene = {{"body", {{"generator", "sphere"}}}};
  RunStatePiece piece;
  piece.name = "front";
  piece.rest.resize(4, 2);
  for (int i = 0; i < 8; ++i) piece.rest(i / 2, i % 2) = kAwkward[i] * (i % 3 == 0 ? -1 : 1);
  piece.triangles.resize(2, 3);
  piece.triangles << 0, 1, 2, 0, 2, 3;
  s.pieces.push_back(piece);
  for (int i = 0; i < 4; ++i) s.state.garment.push_back({i + 3, kAwkward[i], kAwkward[7 - i] / 4});
  s.state.body.resize(3, 3);
  for (int i = 0; i < 9; ++i) s.state.body(i / 3, i % 3) = kAwkward[i % 8] + i;
  s.result = {{"counts", {{"dofs", 12}}}};
  if (command == "optimize") {
    s.term_names = {"stretch", "seam length"};
    OptimizationIteration it;
    it.iteration = 0;
    it.value = kAwkward[1];
    it.term_values = {kAwkward[0], kAwkward[2]};
    it.gradient_norm = kAwkward[3];
    s.history.push_back(it);
  }
  return s;
}

bool bit_equal(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RunState, RoundTripIsBitExact) {
  for (const std::string command : {"simulate", "layout", "optimize"}) {
    const RunState s = sample_state(command);
    const std::string text = run_state_json(s).dump();
    const RunState r = run_state_from_json(nlohmann::json::parse(text), "state.json");
    EXPECT_EQ(r.command, command);
    EXPECT_EQ(r.scene_file, s.scene_file);
    EXPECT_EQ(r.scene_base_dir, s.scene_base_dir);
    EXPECT_EQ(r.scene, s.scene);
    ASSERT_EQ(r.pieces.size(), 1u);
    EXPECT_EQ(r.pieces[0].name, "front");
    EXPECT_EQ(r.pieces[0].triangles, s.pieces[0].triangles);
    for (Eigen::Index i = 0; i < s.pieces[0].rest.size(); ++i)
      EXPECT_TRUE(bit_equal(r.pieces[0].rest.data()[i], s.pieces[0].rest.data()[i])) << i;
    ASSERT_EQ(r.state.garment.size(), s.state.garment.size());
    for (size_t i = 0; i < s.state.garment.size(); ++i) {
      EXPECT_EQ(r.state.garment[i].face, s.state.garment[i].face);
      EXPECT_TRUE(bit_equal(r.state.garment[i].u, s.state.garment[i].u));
      EXPECT_TRUE(bit_equal(r.state.garment[i].v, s.state.garment[i].v));
    }
    ASSERT_EQ(r.state.body.rows(), 3);
    for (Eigen::Index i = 0; i < s.state.body.size(); ++i)
      EXPECT_TRUE(bit_equal(r.state.body.data()[i], s.state.body.data()[i])) << i;
    EXPECT_EQ(r.result, s.result);
    EXPECT_EQ(r.term_names, s.term_names);
    ASSERT_EQ(r.history.size(), s.history.size());
    if (!s.history.empty()) {
      EXPECT_TRUE(bit_equal(r.history[0].value, s.history[0].value));
      EXPECT_TRUE(bit_equal(r.history[0].term_values[1], s.history[0].term_values[1]));
    }
    // Written again, the document is the same text.
    EXPECT_EQ(run_state_json(r).dump(), text);
  }
}

std::string read_error(const nlohmann::json& j);

/// The sample state with a complete (remeshed) pattern of its one piece: a square with
/// a seam joining its left and right edges and a pinned bottom edge.
/// A strip of three unit squares, bottom 0-1-2-3, top 4-5-6-7 (right to left).
/// `flipped` picks the other diagonal in every square.
Triangles strip_triangles(bool flipped) {
  Triangles t(6, 3);
  for (int c = 0; c < 3; ++c) {
    const int b0 = c, b1 = c + 1, t0 = 7 - c, t1 = 6 - c;
    if (flipped)
      t.block<2, 3>(2 * c, 0) << b0, b1, t0, b1, t1, t0;
    else
      t.block<2, 3>(2 * c, 0) << b0, b1, t1, b0, t1, t0;
  }
  return t;
}

RunState remeshed_state() {
  RunState s = sample_state("optimize");
  Pattern p;
  PatternPiece piece;
  piece.name = "front";
  piece.rest.resize(8, 2);
  for (int c = 0; c <= 3; ++c) {
    piece.rest.row(c) << c * kAwkward[0], 0.0;
    piece.rest.row(7 - c) << c * kAwkward[0], kAwkward[1];
  }
  piece.triangles = strip_triangles(false);
  piece.boundary = {0, 1, 2, 3, 4, 5, 6, 7};
  piece.corners = {0, 3, 4, 7};
  piece.grain = Vec2(kAwkward[0], kAwkward[1]);
  p.pieces.push_back(piece);
  // The strip's ends sewn together: a tube three squares round.
  p.seams.push_back({"side", {0, {0, 7}}, {0, {3, 4}}});
  p.pinned.push_back({"hem", 0, {0, 1}});
  s.pattern = p;
  s.state.garment.clear();  // the seam welds 8 pattern vertices into 6
  for (int i = 0; i < 6; ++i) s.state.garment.push_back({i + 3, 0.125 * (i % 3), 0.25});
  return s;
}

TEST(RunState, RemeshedPatternRoundTripIsBitExact) {
  const RunState s = remeshed_state();
  const std::string text = run_state_json(s).dump();
  const RunState r = run_state_from_json(nlohmann::json::parse(text), "state.json");
  ASSERT_TRUE(r.pattern.has_value());
  const PatternPiece& a = s.pattern->pieces[0];
  const PatternPiece& b = r.pattern->pieces[0];
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.triangles, a.triangles);
  EXPECT_EQ(b.boundary, a.boundary);
  EXPECT_EQ(b.corners, a.corners);
  EXPECT_TRUE(bit_equal(b.grain.x(), a.grain.x()) && bit_equal(b.grain.y(), a.grain.y()));
  for (Eigen::Index i = 0; i < a.rest.size(); ++i)
    EXPECT_TRUE(bit_equal(b.rest.data()[i], a.rest.data()[i])) << i;
  ASSERT_EQ(r.pattern->seams.size(), 1u);
  EXPECT_EQ(r.pattern->seams[0].a.vertices, (std::vector<int>{0, 7}));
  EXPECT_EQ(r.pattern->seams[0].b.vertices, (std::vector<int>{3, 4}));
  ASSERT_EQ(r.pattern->pinned.size(), 1u);
  EXPECT_EQ(r.pattern->pinned[0].vertices, (std::vector<int>{0, 1}));
  // The short piece list follows the saved pattern.
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_EQ(r.pieces[0].triangles, a.triangles);
  EXPECT_EQ(run_state_json(r).dump(), text);
}

TEST(RunState, RemeshedPatternIsWeldedAndCheckedAgainstTheScene) {
  const RunState s = remeshed_state();
  Body body;
  body.volume.vertices = s.state.body;
  // The scene's pattern: the same piece, seam and pinned edge with another mesh.
  Pattern scene = *s.pattern;
  scene.pieces[0].triangles = strip_triangles(true);
  const Garment scene_garment = weld_pattern(scene);
  const Garment g = run_state_garment(s, scene_garment, body, 100, "state.json");
  EXPECT_EQ(g.num_garment_vertices(), 6);
  EXPECT_EQ(g.pattern.pieces[0].triangles, s.pattern->pieces[0].triangles);
  EXPECT_EQ(g.embedding.size(), 6u);
  auto error = [&](const RunState& state) {
    try {
      run_state_garment(state, scene_garment, body, 100, "state.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  RunState bad = s;
  bad.pattern->seams[0].name = "other";
  EXPECT_NE(error(bad).find("state.json: /pattern/seams/0/name"), std::string::npos) << error(bad);
  bad = s;
  bad.pattern->pinned.clear();
  EXPECT_NE(error(bad).find("state.json: /pattern/pinned: 0 pinned"), std::string::npos)
      << error(bad);
  bad = s;
  bad.state.garment.resize(4);
  EXPECT_NE(error(bad).find("state.json: /garment: 4 surface points, the saved pattern's"),
            std::string::npos)
      << error(bad);
  // The reader checks the pattern's own consistency.
  nlohmann::json j = run_state_json(s);
  j["pattern"]["seams"][0]["b"]["vertices"] = {1};
  EXPECT_NE(read_error(j).find("/pattern/seams/0: the sides have 2 and 1 vertices"),
            std::string::npos)
      << read_error(j);
  j = run_state_json(s);
  j["pattern"]["pieces"][0]["boundary"] = {0, 1, 1};
  EXPECT_NE(read_error(j).find("/pattern/pieces/0/boundary: the loop repeats"), std::string::npos)
      << read_error(j);
  j = run_state_json(s);
  j["pattern"]["pinned"][0]["piece"] = 3;
  EXPECT_NE(read_error(j).find("/pattern/pinned/0/piece: piece 3 does not exist"),
            std::string::npos)
      << read_error(j);
  j = run_state_json(s);
  j["pattern"]["remeshed"] = false;
  EXPECT_NE(read_error(j).find("/pattern/remeshed"), std::string::npos) << read_error(j);
}

TEST(RunState, StackedRestFollowsPieceOrder) {
  RunState s = sample_state("simulate");
  RunStatePiece second;
  second.name = "back";
  second.rest = Points2::Constant(2, 2, 7.0);
  s.pieces.push_back(second);
  const Points2 rest = stacked_rest_positions(s);
  ASSERT_EQ(rest.rows(), 6);
  EXPECT_EQ(rest.topRows(4), s.pieces[0].rest);
  EXPECT_EQ(rest.bottomRows(2), second.rest);
}

TEST(RunState, SceneFolderIsSavedAbsolute) {
  SceneSpec spec;
  spec.file = "scene.json";
  spec.base_dir = ".";
  spec.document = {{"body", nullptr}};
  const RunState s = make_run_state("layout", spec, Garment{}, EmbeddedState{});
  EXPECT_EQ(s.scene_base_dir, fs::current_path());
  spec.base_dir = "examples/../data";
  EXPECT_EQ(make_run_state("layout", spec, Garment{}, EmbeddedState{}).scene_base_dir,
            fs::current_path() / "data");
  EXPECT_EQ(s.scene, spec.document);
  EXPECT_EQ(s.scene_file, "scene.json");
}

/// The InputError message of reading `j`, or "" when it reads.
std::string read_error(const nlohmann::json& j) {
  try {
    run_state_from_json(j, "run/state.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "run/state.json");
    return e.what();
  }
  return "";
}

TEST(RunState, InitialGarmentRoundTripsAndIsChecked) {
  RunState s = sample_state("optimize");
  TriMesh initial;
  initial.vertices.resize(3, 3);
  for (int i = 0; i < 9; ++i) initial.vertices(i / 3, i % 3) = kAwkward[i % 8];
  initial.faces.resize(1, 3);
  initial.faces << 0, 1, 2;
  s.initial_garment = initial;
  const nlohmann::json j = run_state_json(s);
  const RunState r = run_state_from_json(j, "state.json");
  ASSERT_TRUE(r.initial_garment.has_value());
  EXPECT_EQ(r.initial_garment->vertices, initial.vertices);
  EXPECT_EQ(r.initial_garment->faces, initial.faces);
  EXPECT_FALSE(run_state_from_json(run_state_json(sample_state("optimize")), "s").initial_garment);
  nlohmann::json bad = j;
  bad["initial_garment"]["triangles"][0][2] = 3;  // only vertices 0..2 exist
  EXPECT_NE(read_error(bad).find("/initial_garment/triangles"), std::string::npos)
      << read_error(bad);
}

TEST(RunState, MalformedDocumentsNameTheJsonPath) {
  const nlohmann::json good = run_state_json(sample_state("optimize"));
  EXPECT_EQ(read_error(good), "");
  auto with = [&](const std::string& pointer, const nlohmann::json& value) {
    nlohmann::json j = good;
    j[nlohmann::json::json_pointer(pointer)] = value;
    return read_error(j);
  };
  EXPECT_NE(with("/version", 2).find("/version: unsupported version"), std::string::npos);
  EXPECT_NE(with("/format", "other").find("/format"), std::string::npos);
  EXPECT_NE(with("/command", "flatten").find("/command"), std::string::npos);
  EXPECT_NE(with("/scene_base_dir", "relative/dir").find("/scene_base_dir"), std::string::npos);
  EXPECT_NE(with("/garment/2", nlohmann::json::array({1, 0.5})).find("/garment/2"),
            std::string::npos);
  EXPECT_NE(with("/body/1/2", "x").find("/body/1/2"), std::string::npos);
  EXPECT_NE(
      with("/pattern/pieces/0/rest/3", nlohmann::json::array({1})).find("/pattern/pieces/0/rest/3"),
      std::string::npos);
  EXPECT_NE(with("/pattern/pieces/0/triangles/1/2", -1).find("/pattern/pieces/0/triangles/1/2"),
            std::string::npos);
  EXPECT_NE(with("/history/iterations/0/objective", "x").find("/history/iterations/0/objective"),
            std::string::npos);
  EXPECT_NE(with("/result", 3).find("/result"), std::string::npos);
  EXPECT_NE(with("/surprise", 1).find("surprise"), std::string::npos);
  nlohmann::json no_body = good;
  no_body.erase("body");
  EXPECT_NE(read_error(no_body).find("body"), std::string::npos);
  EXPECT_NE(read_error(nlohmann::json::array()).find("expected a JSON object"), std::string::npos);
}

TEST(RunState, AbsurdCoordinatesAreInputErrorsNamingTheFile) {
  nlohmann::json j = run_state_json(sample_state("simulate"));
  j["body"][1][2] = 1e308;
  try {
    run_state_from_json(j, "run/state.json");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("run/state.json: /body/1/2: 1e+308 m is not a coordinate"),
              std::string::npos)
        << e.what();
  }
  j = run_state_json(sample_state("simulate"));
  j["garment"][0] = {3, 1e300, 0.25};
  EXPECT_THROW(run_state_from_json(j, "run/state.json"), InputError);
}

TEST(RunState, FileErrorsNameTheFile) {
  const fs::path dir =
      fs::temp_directory_path() / ("tightfit_run_state_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "state.json";
  EXPECT_THROW(
      try { read_run_state(file); } catch (const InputError& e) {
        EXPECT_EQ(e.source(), file.string());
        throw;
      },
      InputError);
  std::ofstream(file) << "{\"format\": ";
  EXPECT_THROW(
      try { read_run_state(file); } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos);
        throw;
      },
      InputError);
  const RunState s = sample_state("layout");
  write_run_state(file, s);
  EXPECT_EQ(run_state_json(read_run_state(file)), run_state_json(s));
  fs::remove_all(dir);
}

}  // namespace tightfit::run_state_test
