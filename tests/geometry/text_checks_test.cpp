// SPDX-License-Identifier: BSD-3-Clause
// The checks on text that reaches messages, JSON and file names (issue #34, finding 5): UTF-8 as
// JSON requires it, names that stay plain, messages that show every byte.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/geometry/plain_name.h"

namespace lmk {
namespace {

TEST(TextChecks, Utf8IsWellFormedOnlyAsRfc3629Says) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(is_valid_utf8("milk.pcd"));
  EXPECT_TRUE(
      is_valid_utf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8d\xb6"));  // e-acute, euro, a bottle
  for (const std::string& bad : {
           std::string("\xff"), std::string("\xc3\x28"),  // a lead byte without its follower
           std::string("\xc0\xaf"),                       // an overlong '/'
           std::string("\xe0\x80\xaf"),                   // an overlong '/' in three bytes
           std::string("\xed\xa0\x80"),                   // a surrogate
           std::string("\xf4\x90\x80\x80"),               // beyond U+10FFFF
           std::string("ok\xe2\x82"),                     // cut short
       }) {
    EXPECT_FALSE(is_valid_utf8(bad)) << printable(bad);
  }
}

TEST(TextChecks, PrintableShowsEveryByteOfANameWithANul) {
  EXPECT_EQ(printable(std::string("milk\0evil", 9)), "milk\\x00evil");
  EXPECT_EQ(printable("\xff.pcd"), "\\xff.pcd");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");
}

TEST(TextChecks, BidirectionalControlsAreShownNotSent) {
  // U+202E would show "milk\u202Edcp.exe" as "milkexe.pcd" (issue #61, finding 8); every
  // bidirectional mark, embedding, override and isolate is escaped, and other letters stay.
  EXPECT_EQ(printable("milk\xe2\x80\xae"
                      "dcp.exe"),
            "milk\\xe2\\x80\\xaedcp.exe");
  for (const char* control :
       {"\xd8\x9c", "\xe2\x80\x8e", "\xe2\x80\x8f", "\xe2\x80\xaa", "\xe2\x80\xab", "\xe2\x80\xac",
        "\xe2\x80\xad", "\xe2\x81\xa6", "\xe2\x81\xa7", "\xe2\x81\xa8", "\xe2\x81\xa9"}) {
    EXPECT_EQ(printable(control).find('\\'), 0u) << printable(control);
    EXPECT_FALSE(is_printable_text(std::string("a") + control));
  }
  // Neighbours that are no controls: an en dash (U+2013), a bullet (U+2022), an Arabic letter.
  for (const std::string text : {"\xe2\x80\x93", "\xe2\x80\xa2", "\xd8\xa8"})
    EXPECT_EQ(printable(text), text);
}

TEST(TextChecks, ControlCharactersOfEveryKindAreShownNotSent) {
  // C0, DEL, and C1 in UTF-8 (U+009B reads as ESC [ on some terminals); other UTF-8 stays.
  EXPECT_EQ(printable("a\x1b[2J\x7f\xc2\x9b"
                      "1m\xc3\xa9"),
            "a\\x1b[2J\\x7f\\xc2\\x9b1m\xc3\xa9");
  EXPECT_TRUE(is_printable_text("caf\xc3\xa9 au lait"));
  for (const std::string& bad : std::vector<std::string>{"a\nb", "\x1b]0;x\x07", "\xc2\x9b", "\x7f",
                                                         "\xff", std::string("a\0b", 3)}) {
    EXPECT_FALSE(is_printable_text(bad)) << printable(bad);
  }
  // Echoed input is cut.
  EXPECT_EQ(printable(std::string(500, 'x'), kEchoedBytes), std::string(kEchoedBytes, 'x') + "...");
}

TEST(TextChecks, PlainNamesCannotLeaveHideOrReadAsAnOption) {
  for (const std::string good : {"milk", "rack-2", "a.b_c", "9"}) {
    EXPECT_TRUE(is_plain_name(good, 100)) << good;
  }
  for (const std::string& bad :
       std::vector<std::string>{"", "-rf", ".hidden", "../up", "a/b", "a b", "caf\xc3\xa9",
                                std::string("a\0b", 3), std::string(101, 'x')}) {
    EXPECT_FALSE(is_plain_name(bad, 100)) << printable(bad);
  }
}

}  // namespace
}  // namespace lmk
