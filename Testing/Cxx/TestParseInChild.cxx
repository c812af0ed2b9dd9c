// mcxio::ParseInChild (IO/mcxDicomFiles.h), which parses what vtk-dicom's
// parser may fault on in a forked child: the answer handed back whole, and
// each way the child can end without one (a signal, an exception, the time
// limit) one line that says which.
#include "mcxDicomFiles.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <stdexcept>
#include <string>
#include <thread>

TEST(ParseInChild, TheAnswerComesBackWhole)
{
  // Larger than a pipe's buffer, with every byte value.
  std::string sent(200000, '\0');
  for (std::size_t i = 0; i < sent.size(); ++i)
  {
    sent[i] = static_cast<char>(i * 7);
  }
  std::string answer, error;
  EXPECT_TRUE(mcxio::ParseInChild([&]() { return sent; }, "it", answer, error)) << error;
  EXPECT_EQ(sent, answer);
  EXPECT_TRUE(mcxio::ParseInChild([]() { return std::string(); }, "it", answer, error));
  EXPECT_EQ("", answer);
}

TEST(ParseInChild, AChildThatEndsWithoutAnAnswerIsOneLineThatSaysHow)
{
  std::string answer, error;
  EXPECT_FALSE(mcxio::ParseInChild(
    []()
    {
      std::raise(SIGSEGV);
      return std::string("never");
    },
    "the plan", answer, error));
  // A sanitizer's runtime reports the fault itself and exits with a status.
  if (MCXRAY_TEST_SANITIZED)
  {
    EXPECT_EQ(0u, error.find("vtk-dicom's parser ")) << error;
    EXPECT_NE(std::string::npos, error.find(") on the plan")) << error;
  }
  else
  {
    EXPECT_EQ("vtk-dicom's parser crashed (SIGSEGV) on the plan", error);
  }
  EXPECT_FALSE(
    mcxio::ParseInChild([]() -> std::string { throw std::runtime_error("thrown in the child"); },
      "the plan", answer, error));
  EXPECT_EQ("vtk-dicom's parser failed (exit status 1) on the plan", error);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(mcxio::ParseInChild(
    []()
    {
      std::this_thread::sleep_for(std::chrono::seconds(60));
      return std::string("late");
    },
    "one of its files", answer, error, 0.25));
  EXPECT_EQ("vtk-dicom's parser did not finish within 0.25 s on one of its files", error);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}
