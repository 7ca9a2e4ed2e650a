#include "tightfit/scene/pattern_record.hpp"
#include "tightfit/garment/pattern_compare.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace pattern_record_test {

/// Two triangles sewn along one edge, the first pinned along another.
Pattern two_triangles() {
  Pattern p;
  for (const char* name : {"front", "back"}) {
    PatternPiece piece;
    piece.name = name;
    piece.rest.resize(3, 2);
    piece.rest << 0, 0, 1, 0, 0, 1;
    piece.triangles.resize(1, 3);
    piece.triangles << 0, 1, 2;
    piece.boundary = {0, 1, 2};
    piece.corners = {0, 1, 2};
    piece.grain = Vec2(0, 1);
    p.pieces.push_back(piece);
  }
  p.seams.push_back({"side", {0, {1, 2}}, {1, {2, 1}}});
  p.pinned.push_back({"waist", 0, {0, 1}});
  return p;
}

/// The message of the InputError check_saved_pattern throws, or "" when it accepts.
std::string saved_pattern_error(const Pattern& saved, const Pattern& scene) {
  try {
    check_saved_pattern(saved, scene, "state.json", "/pattern", " (changed?)");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PatternRecord, SavedPatternMustKeepTheScenePiecesSeamsAndPins) {
  const Pattern scene = two_triangles();
  EXPECT_EQ(saved_pattern_error(scene, scene), "");
  Pattern remeshed = scene;  // another mesh of the same pieces is accepted
  remeshed.pieces[1].rest.conservativeResize(4, 2);
  remeshed.pieces[1].rest.row(3) << 0.3, 0.3;
  remeshed.pieces[1].triangles.resize(3, 3);
  remeshed.pieces[1].triangles << 0, 1, 3, 1, 2, 3, 2, 0, 3;
  EXPECT_EQ(saved_pattern_error(remeshed, scene), "");
  EXPECT_FALSE(same_pattern_meshes(remeshed, scene));

  Pattern bad = scene;
  bad.pieces[1].name = "sleeve";
  EXPECT_EQ(saved_pattern_error(bad, scene),
            "state.json: /pattern/pieces/1/name: \"sleeve\", the scene's is \"back\" (changed?)");
  bad = scene;
  bad.seams[0].b.piece = 0;
  EXPECT_EQ(saved_pattern_error(bad, scene),
            "state.json: /pattern/seams/0/b/piece: piece 0, the scene's is piece 1 (changed?)");
  bad = scene;
  bad.pinned.clear();
  EXPECT_EQ(saved_pattern_error(bad, scene),
            "state.json: /pattern/pinned: 0 pinned, the scene's pattern has 1 (changed?)");
}

TEST(PatternRecord, ExtraKeysAreAcceptedOnlyWhereDeclared) {
  const Pattern p = two_triangles();
  nlohmann::json j = pattern_record_json(p);
  j["pieces"][0]["quantity"] = 2;
  j["seams"][0]["a"]["piece_name"] = "front";
  try {
    pattern_record_from_json(j, "f.json", "");
    ADD_FAILURE() << "an unknown key was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.json: /pieces/0/quantity: unknown key"),
              std::string::npos)
        << e.what();
  }
  PatternRecordExtraKeys extra;
  extra.piece = {"quantity"};
  extra.side = {"piece_name"};
  const Pattern read = pattern_record_from_json(j, "f.json", "", extra);
  EXPECT_TRUE(same_pattern_meshes(read, p));
  EXPECT_EQ(pattern_record_json(read), pattern_record_json(p));
}

}  // namespace pattern_record_test
}  // namespace tightfit
