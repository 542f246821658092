// PrintableText: what a corrupt file's bytes become in a message or a glTF name.
#include <OpenMeshSkinned/IO/PrintableText.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

TEST(PrintableText, ValidUtf8IsKeptAndEverythingElseBecomesAQuestionMark) {
  EXPECT_EQ(printable_text("Bip01 Spine"), "Bip01 Spine");
  EXPECT_EQ(printable_text("K\xc3\xb6rper \xe9\xaa\xa8\xf0\x9f\xa6\xb4"), "K\xc3\xb6rper \xe9\xaa\xa8\xf0\x9f\xa6\xb4");
  EXPECT_EQ(printable_text("a\xff"
                           "b\x80"
                           "c"),
            "a?b?c");                                       // bytes that start no character
  EXPECT_EQ(printable_text("\xc0\xaf"), "??");              // an overlong '/'
  EXPECT_EQ(printable_text("\xed\xa0\x80"), "???");         // a UTF-16 surrogate
  EXPECT_EQ(printable_text("\xf4\x90\x80\x80"), "????");    // beyond U+10FFFF
  EXPECT_EQ(printable_text("\xe9\xaa"), "??");              // cut short
  EXPECT_EQ(printable_text("x\x1b[31my\x7f"), "x?[31my?");  // a terminal escape, DEL
  EXPECT_EQ(printable_text("\xc2\x85"), "?");               // a C1 control (NEL)
  EXPECT_EQ(printable_text(std::string("a\0b", 3)), "a?b");
}

TEST(PrintableText, ALineHasNoBreaksAndIsCutOnACharacterBoundary) {
  EXPECT_EQ(printable_line("first\nsecond\r\n"), "first second");
  EXPECT_EQ(printable_line("tab\there"), "tab here");
  EXPECT_EQ(printable_line("abcdef", 4), "abcd [...]");
  // "\xc3\xb6" is one character of two bytes: a cut after byte 2 would split it.
  EXPECT_EQ(printable_line("a\xc3\xb6"
                           "bc",
                           2),
            "a [...]");
  EXPECT_EQ(printable_line("short", 240), "short");
}
