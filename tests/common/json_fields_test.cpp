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

TEST(JsonText, ASyntaxErrorNamesFileLineAndColumnInTheEditorsForm) {
  try {
    parse_json_text("{\"body\": {\"radius\": 0.1,}\n}", "scene.json");
    ADD_FAILURE() << "a trailing comma parsed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("scene.json:1:25: invalid JSON: syntax error", 0), 0u)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
  }
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

/// The message of the InputError `read` throws, or "" when it throws none.
template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonFields, AnExplicitNullIsAnErrorNeverTheDefault) {
  const auto j = nlohmann::json::parse(
      R"({"body": null, "n": null, "s": null, "v": null, "b": null, "x": null, "list": null})");
  JsonFields f(j, "scene.json", "");
  EXPECT_EQ(error_of([&] { f.object("body", true); }),
            "scene.json: /body: is null (expected an object)");
  EXPECT_NE(error_of([&] { f.object("body"); }).find("leave the key out for the default"),
            std::string::npos);
  EXPECT_NE(error_of([&] { f.integer("n", 3); }).find("/n: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.string("s"); }).find("/s: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.vec3("v", Vec3::Zero()); }).find("/v: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.boolean("b", true); }).find("/b: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.number("x", 1.0); }).find("/x: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.positive("x", 1.0); }).find("/x: is null"), std::string::npos);
  EXPECT_NE(error_of([&] { f.objects("list"); }).find("/list: is null"), std::string::npos);
  EXPECT_TRUE(f.raw("x").is_null());  // raw() hands the value over as it is
}

TEST(JsonFields, OutOfRangeNumbersSaySo) {
  const auto j = nlohmann::json::parse(
      R"({"big": 2147483648, "huge": 18446744073709551615, "low": -2147483649, "ok": 2147483647,
          "e": 1e308, "v": [0, 1e300, 0], "m": 5e12})");
  JsonFields f(j, "s.json", "");
  EXPECT_NE(error_of([&] { f.integer("big"); }).find("/big: is 2147483648, out of range"),
            std::string::npos);
  EXPECT_NE(error_of([&] { f.integer("huge"); }).find("out of range"), std::string::npos);
  EXPECT_NE(error_of([&] { f.integer("low"); }).find("out of range"), std::string::npos);
  EXPECT_EQ(f.integer("ok"), 2147483647);
  EXPECT_NE(error_of([&] { f.number("e"); }).find("/e: is 1e+308, beyond"), std::string::npos);
  EXPECT_NE(error_of([&] { f.vec3("v"); }).find("/v: holds 1e+300"), std::string::npos);
  EXPECT_EQ(error_of([&] { f.at_most("m", f.number("m"), 1e12, "why"); }),
            "s.json: /m: is 5e+12, more than 1e+12 (why)");
}

TEST(JsonFields, AbsurdCountsOfPartsAreRefused) {
  nlohmann::json j;
  j["planes"] = nlohmann::json::array();
  for (int k = 0; k < 300; ++k) j["planes"].push_back({{"k", k}});
  JsonFields f(j, "s.json", "");
  EXPECT_NE(error_of([&] {
              f.objects("planes", false, kMaxSceneParts);
            }).find("/planes: lists 300 entries, more than 256"),
            std::string::npos);
  EXPECT_EQ(f.objects("planes").size(), 300u);  // no limit unless one is asked for
}

TEST(JsonText, RepeatedKeysAreAnErrorNamingTheKeyAndBothLines) {
  const std::string text =
      "{\n  \"fabric\": {\n    \"youngs_modulus\": 1e5,\n    \"thickness\": 0.001,\n"
      "    \"youngs_modulus\": 1e9\n  }\n}\n";
  EXPECT_EQ(error_of([&] { parse_json_text(text, "scene.json"); }),
            "scene.json: invalid JSON: key \"youngs_modulus\" given twice in one object (lines 3 "
            "and 5): only one value can count; remove the other");
  // The same key in different objects, in arrays or in strings is fine; an escaped spelling
  // of the same key is the same key.
  EXPECT_NO_THROW(parse_json_text(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 1}, {"x": 2}],
                                      "d": "\"x\": 1, \"x\": 2"})",
                                  "x"));
  EXPECT_NE(error_of([&] {
              parse_json_text(R"({"x": 1, "\u0078": 2})", "s.json");
            }).find("key \"x\" given twice"),
            std::string::npos);
}

}  // namespace tightfit::json_fields_test
