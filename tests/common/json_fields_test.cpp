#include "tightfit/common/json_fields.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit::json_fields_test {

TEST(JsonFields, ReadsTypedFieldsWithDefaults) {
  const auto j =
      nlohmann::json::parse(R"({"a": 2.5, "n": 3, "s": "x", "v": [1,2,3], "o": {"b": true}})");
  JsonFields f(j, "scene.json", "");
  EXPECT_EQ(f.number("a"), 2.5);
  EXPECT_EQ(f.integer("n"), 3);
  EXPECT_EQ(f.string("s"), "x");
  EXPECT_EQ(f.vec3("v"), Vec3(1, 2, 3));
  EXPECT_EQ(f.number("missing", 7.0), 7.0);
  auto o = f.object("o");
  ASSERT_TRUE(o);
  EXPECT_TRUE(o->boolean("b"));
  o->finish();
  f.finish();
}

TEST(JsonFields, NamesFileAndPathOfWrongTypes) {
  const auto j = nlohmann::json::parse(R"({"body": {"edge_length": "small"}})");
  JsonFields f(j, "scene.json", "");
  auto body = f.object("body", true);
  try {
    body->number("edge_length");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: /body/edge_length: expected a number, got string");
  }
}

TEST(JsonFields, RejectsUnknownKeys) {
  const auto j = nlohmann::json::parse(R"({"a": 1, "typo": 2})");
  JsonFields f(j, "s.json", "/x");
  f.number("a");
  try {
    f.finish();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/x/typo: unknown key"), std::string::npos);
  }
}

TEST(JsonFields, RejectsNonPositiveAndBadChoices) {
  const auto j = nlohmann::json::parse(R"({"e": -1, "m": "quux"})");
  JsonFields f(j, "s.json", "");
  EXPECT_THROW(f.positive("e"), InputError);
  EXPECT_THROW(f.choice("m", {"a", "b"}), InputError);
  EXPECT_THROW(f.number("absent"), InputError);
}

TEST(JsonText, DeepNestingIsAnInputErrorBeforeParsing) {
  // A million brackets would overflow the stack in nlohmann's recursive copy and dump.
  const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
  try {
    parse_json_text(deep, "deep.json");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("deep.json: invalid JSON: nested deeper than 256"),
              std::string::npos)
        << e.what();
  }
  std::string objects;
  for (int k = 0; k < 300; ++k) objects += "{\"a\":";
  objects += "1" + std::string(300, '}');
  EXPECT_THROW(parse_json_text(objects, "x"), InputError);
  // At the limit it parses; brackets inside strings (with escaped quotes) do not count.
  const std::string at_limit = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_NO_THROW(parse_json_text(at_limit, "x"));
  const nlohmann::json j = parse_json_text(R"({"s": "[[[{{{\"[[[", "t": [1]})", "x");
  EXPECT_EQ(j["t"][0], 1);
  EXPECT_THROW(parse_json_text("{\"a\": ", "x"), InputError);
}

}  // namespace tightfit::json_fields_test
