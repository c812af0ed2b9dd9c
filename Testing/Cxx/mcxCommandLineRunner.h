// Runs the mcxray command as a user would, for the command-line tests:
// its exit status, stdout and stderr, and the one-line error contract.
#ifndef mcxCommandLineRunner_h
#define mcxCommandLineRunner_h

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"
#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace mcxtest
{

struct Result
{
  int Status;
  std::string Output; // stdout
  std::string Errors; // stderr
};

inline std::string Slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Files of folder whose names contain part (leftover temporaries).
inline int CountFiles(const std::string& folder, const std::string& part)
{
  vtksys::Directory directory;
  directory.Load(folder);
  int count = 0;
  for (unsigned long f = 0; f < directory.GetNumberOfFiles(); ++f)
  {
    count += std::string(directory.GetFile(f)).find(part) != std::string::npos ? 1 : 0;
  }
  return count;
}

inline Result RunCLI(const std::string& arguments, const std::string& environment = "")
{
  // One log per test: ctest may run the tests of this file in parallel.
  const std::string log = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/mcxray-" +
    ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string command = environment + std::string(MCXRAY_CLI) + " " + arguments + " > " +
    log + ".out 2> " + log + ".err";
  const int raw = std::system(command.c_str());
  return { WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, Slurp(log + ".out"), Slurp(log + ".err") };
}

inline vtkSmartPointer<vtkImageData> Read(const std::string& path)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

inline std::string Temporary(const std::string& name)
{
  const std::string path = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/" + name;
  vtksys::SystemTools::RemoveFile(path);
  return path;
}

// Exit status 2, one line on stderr, nothing on stdout, no output file.
inline void ExpectOneLineError(const std::string& arguments, const std::string& output)
{
  Result r = RunCLI(arguments);
  EXPECT_EQ(2, r.Status) << arguments << "\n" << r.Errors;
  EXPECT_EQ(0u, r.Errors.find("mcxray: error: ")) << arguments << "\n" << r.Errors;
  EXPECT_EQ(r.Errors.size() - 1, r.Errors.find('\n')) << arguments << "\n" << r.Errors;
  EXPECT_EQ("", r.Output) << arguments;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << arguments;
}

} // namespace mcxtest

#endif
