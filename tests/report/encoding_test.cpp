#include "tightfit/report/encoding.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tightfit/common/finite_output.hpp"

namespace tightfit::report_encoding_test {

TEST(ReportEncoding, Base64Rfc4648Vectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(ReportEncoding, TypedArraysAreLittleEndian) {
  // 1.0f = 0x3f800000 → bytes 00 00 80 3f.
  EXPECT_EQ(base64_float32({1.0}), base64_encode(std::string("\x00\x00\x80\x3f", 4)));
  EXPECT_EQ(base64_uint32({1, 258}),
            base64_encode(std::string("\x01\x00\x00\x00\x02\x01\x00\x00", 8)));
  // No report carries a NaN or an infinity (common/finite_output.hpp).
  EXPECT_THROW(base64_float32({1.0, std::nan("")}), NonFiniteOutput);
  EXPECT_THROW(base64_float32({HUGE_VAL}), NonFiniteOutput);
  EXPECT_THROW(base64_uint32({-1}), std::invalid_argument);
}

TEST(ReportEncoding, JsonForScriptHasNoTagsAndParsesBack) {
  const nlohmann::json j = {{"name", "</script><!-- x"}, {"v", 1.5}};
  const std::string text = json_for_script(j);
  EXPECT_EQ(text.find('<'), std::string::npos) << text;
  EXPECT_EQ(nlohmann::json::parse(text), j);
  EXPECT_THROW(json_for_script({{"v", std::nan("")}}), NonFiniteOutput);
}

}  // namespace tightfit::report_encoding_test
