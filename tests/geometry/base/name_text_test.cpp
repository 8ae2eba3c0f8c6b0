// geometry/base/name_text.h: names shown as written (issue 28: byte 0xFF made report.json and
// manifest.json invalid UTF-8; bidi overrides and blank names were accepted).
#include "geometry/base/name_text.h"

#include <gtest/gtest.h>

namespace windplan {
namespace {

std::string why_not(const std::string& name) {
  std::string why;
  return check_name_text(name, &why) ? "" : why;
}

TEST(NameText, UnicodeNamesAreFine) {
  EXPECT_EQ(why_not("pipe"), "");
  EXPECT_EQ(why_not("Druckbehälter 2"), "");
  EXPECT_EQ(why_not("圧力容器"), "");
  EXPECT_EQ(why_not("tank \xF0\x9F\x9A\x80"), "");  // U+1F680
  EXPECT_EQ(why_not("a\xC2\xA0"
                    "b"),
            "");  // a no-break space inside a name
}

TEST(NameText, BytesThatAreNotUtf8AreRefusedWithTheirPlace) {
  EXPECT_EQ(why_not("ab\xFF"), "is not valid UTF-8 (byte 0xFF at byte 3)");
  EXPECT_EQ(why_not("\xC3"), "is not valid UTF-8 (byte 0xC3 at byte 1)");          // cut short
  EXPECT_EQ(why_not("\xC0\xAF"), "is not valid UTF-8 (byte 0xC0 at byte 1)");      // overlong '/'
  EXPECT_EQ(why_not("\xE0\x80\xAF"), "is not valid UTF-8 (byte 0xE0 at byte 1)");  // overlong
  EXPECT_EQ(why_not("\xED\xA0\x80"), "is not valid UTF-8 (byte 0xED at byte 1)");  // surrogate
  EXPECT_EQ(why_not("\xF4\x90\x80\x80"), "is not valid UTF-8 (byte 0xF4 at byte 1)");
}

TEST(NameText, ControlFormatAndBlankNamesAreRefused) {
  EXPECT_EQ(why_not("a\x7f"), "must not contain control characters (U+007F)");
  EXPECT_EQ(why_not("a\xC2\x85"), "must not contain control characters (U+0085)");
  EXPECT_NE(why_not("evil\xE2\x80\xAEgpj.exe").find("invisible format character U+202E"),
            std::string::npos);
  EXPECT_NE(why_not("a\xE2\x80\x8B"
                    "b")
                .find("U+200B"),
            std::string::npos);
  EXPECT_NE(why_not("\xEF\xBB\xBFpipe").find("U+FEFF"), std::string::npos);
  EXPECT_EQ(why_not("\xC2\xA0\xC2\xA0"), "is blank (only spaces)");
  EXPECT_EQ(why_not("   "), "is blank (only spaces)");
  EXPECT_EQ(why_not("\xE3\x80\x80"), "is blank (only spaces)");  // ideographic space
}

}  // namespace
}  // namespace windplan
