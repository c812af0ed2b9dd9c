// mcx::PrintableText (Core/mcxPrintableText.h), the guard of every error
// line that quotes a file's bytes: without a pipeline.
#include "mcxPrintableText.h"

#include <gtest/gtest.h>

#include <string>

TEST(PrintableText, KeepsPrintableASCIIAndUTF8)
{
  EXPECT_EQ("cannot read '/data/x.nrrd': type 'int8'",
    mcx::PrintableText("cannot read '/data/x.nrrd': type 'int8'"));
  // A patient's name in a path: two-, three- and four-byte sequences.
  const std::string utf8 = "/scans/M\xc3\xbcller/\xe6\x9d\x8e/\xf0\x9f\xa6\xb4.nii";
  EXPECT_EQ(utf8, mcx::PrintableText(utf8));
}

TEST(PrintableText, EscapesControlsAndWhatIsNoUTF8)
{
  EXPECT_EQ("a\\x0ab\\x1b[2Jc\\x7f", mcx::PrintableText("a\nb\x1b[2Jc\x7f"));
  EXPECT_EQ("\\x00", mcx::PrintableText(std::string(1, '\0')));
  // Lone continuation, lead bytes never valid, a cut sequence, an overlong
  // form, a surrogate, a C1 control (U+0085), beyond U+10FFFF.
  EXPECT_EQ("\\xb4\\xff\\xb4", mcx::PrintableText("\xb4\xff\xb4"));
  EXPECT_EQ("\\xc0\\xaf", mcx::PrintableText("\xc0\xaf"));
  EXPECT_EQ("x\\xe6\\x9d", mcx::PrintableText("x\xe6\x9d"));
  EXPECT_EQ("\\xe0\\x80\\xaf", mcx::PrintableText("\xe0\x80\xaf"));
  EXPECT_EQ("\\xed\\xa0\\x80", mcx::PrintableText("\xed\xa0\x80"));
  EXPECT_EQ("\\xc2\\x85", mcx::PrintableText("\xc2\x85"));
  EXPECT_EQ("\\xf4\\x90\\x80\\x80", mcx::PrintableText("\xf4\x90\x80\x80"));
}

TEST(PrintableText, CutsALongTextInItsMiddle)
{
  const std::string text = "cannot read '" + std::string(100000, 'a') + "': the reason";
  const std::string shown = mcx::PrintableText(text, 2048);
  EXPECT_LE(shown.size(), 2048u);
  EXPECT_EQ(0u, shown.find("cannot read 'aaa"));
  EXPECT_NE(std::string::npos, shown.find(" ... "));
  EXPECT_EQ(shown.size() - 13, shown.rfind("': the reason"));
  // Never between the bytes of one UTF-8 sequence.
  std::string wide;
  for (int i = 0; i < 3000; ++i)
  {
    wide += "\xc3\xbc";
  }
  const std::string cut = mcx::PrintableText(wide, 2048);
  EXPECT_EQ(cut, mcx::PrintableText(cut, 1 << 20)); // still valid UTF-8: unchanged
}
