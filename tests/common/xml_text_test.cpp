#include "tightfit/common/xml_text.hpp"

#include <gtest/gtest.h>

namespace tightfit::xml_text_test {

TEST(XmlText, EscapesTheFiveSpecialCharactersAndControls) {
  EXPECT_EQ(xml_escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
  EXPECT_EQ(xml_escape("tab\tline\nbell\x07"), "tab\tline\nbell ");
  EXPECT_EQ(xml_escape("Ärmel 10 mm"), "Ärmel 10 mm");  // UTF-8 passes through
}

TEST(XmlText, UnescapeInvertsEscape) {
  for (const char* text : {"plain", "a<b>&\"c'", "&amp;lt; literally", "x & y"})
    EXPECT_EQ(xml_unescape(xml_escape(text)), text);
  EXPECT_EQ(xml_unescape("&apos;&#39;&unknown;"), "''&unknown;");
}

}  // namespace tightfit::xml_text_test
