// Hostile process conditions (issue 39): limits on address space, CPU time,
// processes and file descriptors, closed pipes, signals during the write,
// and options that would run without end. Every case must end within a
// bound with exit status 2 (or the signal's documented outcome), exactly
// one line on stderr, and neither the output nor a temporary left behind.
#include "mcxCommandLineRunner.h"
#include "mcxTestHelpers.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkXMLImageDataWriter.h"
#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using mcxtest::CountFiles;
using mcxtest::Slurp;
using mcxtest::Temporary;

namespace
{
const std::string BadSLC = MCXRAY_TEST_DATA_DIR "/Hostile/rle-run-overflow.slc";

// How the child is started: its limits (0: inherited), its stdin closed,
// its stdout a pipe nobody reads, a signal sent once a file whose name
// contains SignalWhen appears in Folder.
struct Conditions
{
  rlim_t AddressSpace = 0;
  rlim_t CPUSeconds = 0;
  rlim_t Processes = 0;
  rlim_t Files = 0;
  bool CloseStdin = false;
  bool CloseStdout = false;
  bool BrokenStdout = false;
  int Signal = 0;
  std::string Folder;
  std::string SignalWhen;
  double Seconds = 120; // the bound: killed (and failed) past it
};

struct Outcome
{
  int Status = -1; // waitpid's
  std::string Output;
  std::string Errors;
  double Seconds = 0;
  bool Signalled = false; // Conditions::Signal was sent
};

// mcxray with arguments, forked and limited as conditions say (setrlimit in
// the child before exec), its stdout and stderr kept in files of log.
Outcome RunMcxray(const std::vector<std::string>& arguments, const Conditions& conditions)
{
  const std::string log = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/mcxray-process-" +
    ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string out = log + ".out", err = log + ".err";
  int broken[2] = { -1, -1 };
  if (conditions.BrokenStdout && ::pipe(broken) == 0)
  {
    ::close(broken[0]); // nobody reads: every write fails with EPIPE
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0)
  {
    const int errors = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int output =
      conditions.BrokenStdout ? broken[1] : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(output, STDOUT_FILENO);
    ::dup2(errors, STDERR_FILENO);
    for (int fd = 3; fd < 1024; ++fd)
    {
      ::close(fd);
    }
    if (conditions.CloseStdin)
    {
      ::close(STDIN_FILENO);
    }
    if (conditions.CloseStdout)
    {
      ::close(STDOUT_FILENO);
    }
    const auto limit = [](int resource, rlim_t value)
    {
      if (value > 0)
      {
        const rlimit both = { value, resource == RLIMIT_CPU ? value + 10 : value };
        ::setrlimit(resource, &both);
      }
    };
    const rlimit noCore = { 0, 0 }; // SIGQUIT's end dumps no core here
    ::setrlimit(RLIMIT_CORE, &noCore);
    limit(RLIMIT_AS, conditions.AddressSpace);
    limit(RLIMIT_CPU, conditions.CPUSeconds);
    limit(RLIMIT_NPROC, conditions.Processes);
    limit(RLIMIT_NOFILE, conditions.Files);
    std::vector<char*> argv = { const_cast<char*>(MCXRAY_CLI) };
    for (const std::string& argument : arguments)
    {
      argv.push_back(const_cast<char*>(argument.c_str()));
    }
    argv.push_back(nullptr);
    ::execv(MCXRAY_CLI, argv.data());
    ::_exit(127);
  }
  if (broken[1] >= 0)
  {
    ::close(broken[1]);
  }
  Outcome outcome;
  const auto elapsed = [&]
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  for (;;)
  {
    if (::waitpid(child, &outcome.Status, WNOHANG) == child)
    {
      break;
    }
    if (conditions.Signal && !outcome.Signalled &&
      CountFiles(conditions.Folder, conditions.SignalWhen) > 0)
    {
      ::kill(child, conditions.Signal);
      outcome.Signalled = true;
    }
    if (elapsed() > conditions.Seconds)
    {
      ::kill(child, SIGKILL);
      ::waitpid(child, &outcome.Status, 0);
      ADD_FAILURE() << "still running after " << conditions.Seconds << " s";
      break;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  outcome.Seconds = elapsed();
  outcome.Output = conditions.BrokenStdout ? std::string() : Slurp(out);
  outcome.Errors = Slurp(err);
  return outcome;
}

int Lines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// Exit status 2, exactly one error line containing needle, and nothing of
// output (nor its temporaries) in folder.
void ExpectOneLine(
  const Outcome& r, const std::string& needle, const std::string& folder, const std::string& output)
{
  EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 2) << "status " << r.Status << "\n"
                                                                 << r.Errors;
  EXPECT_EQ(0u, r.Errors.find("mcxray: error: ")) << r.Errors;
  EXPECT_EQ(1, Lines(r.Errors)) << r.Errors;
  EXPECT_NE(std::string::npos, r.Errors.find(needle)) << r.Errors;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << output;
  EXPECT_EQ(0, CountFiles(folder, ".part-")) << folder;
}

std::string Folder(const std::string& name)
{
  const std::string folder = Temporary(name);
  vtksys::SystemTools::RemoveADirectory(folder);
  vtksys::SystemTools::MakeDirectory(folder);
  return folder;
}
}

TEST(HostileProcess, TinyPixelsAndAnglesKeepTheFootprintTablesBounded)
{
  // 1e-9 mm pixels (voxels of 1e9 pixels) and a perspective of 1e-9 degrees
  // grew the footprint tables without end; now they are bounded by the
  // reach and checked against the budget: an image (all of it off the
  // volume's centre, or a tiny part of one voxel) within seconds.
  const std::string folder = Folder("process_footprint");
  const std::string output = folder + "/tiny.vti";
  for (const std::vector<std::string>& view :
    { std::vector<std::string>{ "--pixel-spacing", "1e-9", "--size", "64x64" },
      std::vector<std::string>{
        "--camera", "100,100,-500:100,100,50:0,1,0:angle=1e-9", "--size", "64x64" } })
  {
    std::vector<std::string> arguments = { "render", "--samples", "65535", "--memory-limit", "2G",
      "--quiet", "--output", output };
    arguments.insert(arguments.end(), view.begin(), view.end());
    Conditions bounded;
    bounded.Seconds = 60;
    // (Not under the sanitizers: their runtime reserves terabytes.)
    bounded.AddressSpace = MCXRAY_TEST_SANITIZED ? 0 : rlim_t(8) << 30;
    const Outcome r = RunMcxray(arguments, bounded);
    EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 0) << r.Status << "\n" << r.Errors;
    EXPECT_TRUE(vtksys::SystemTools::FileExists(output)) << view[1];
    vtksys::SystemTools::RemoveFile(output);
  }
  // A budget that holds the volume and its index but not the tables (6.7
  // MiB for this view) is one line before they exist.
  const Outcome r = RunMcxray(
    { "render", "--samples", "1023", "--memory-limit", "5M", "--camera",
      "100,100,-500:100,100,50:0,1,0:angle=1e-9", "--size", "1x1", "--quiet", "--output", output },
    Conditions());
  ExpectOneLine(r, "the footprint tables of this view need", folder, output);
}

TEST(HostileProcess, StoredPointsUnderAnAddressSpaceLimitAreOneLine)
{
  if (MCXRAY_TEST_SANITIZED)
  {
    GTEST_SKIP() << "a process limit the sanitizers' runtimes cannot live under (the unsanitized "
                    "build runs it)";
  }
  // 2^30 - 1 points fit the budget (the machine's memory) but not 3 GiB of
  // address space: the failed allocation is one line, not an abort.
  const std::string folder = Folder("process_address_space");
  const std::string output = folder + "/cloud.png";
  Conditions limited;
  limited.AddressSpace = rlim_t(3) << 30;
  limited.Seconds = 60;
  const Outcome r = RunMcxray(
    { "render", "--stored-points", "--samples", "1073741823", "--quiet", "--output", output },
    limited);
  ExpectOneLine(r, "points", folder, output);
}

TEST(HostileProcess, NoChildForTheReaderIsOneLineAndNoReadInProcess)
{
  if (MCXRAY_TEST_SANITIZED)
  {
    GTEST_SKIP() << "a process limit the sanitizers' runtimes cannot live under (the unsanitized "
                    "build runs it)";
  }
  // With three file descriptors and stdin closed, the shared memory of the
  // contained read cannot be moved above stderr: the read must not fall
  // back to the reader in this process (this SLC overruns vtkSLCReader's
  // buffer and aborts it), but fail in one line.
  const std::string folder = Folder("process_no_child");
  const std::string output = folder + "/never.png";
  Conditions few;
  few.Files = 3;
  few.CloseStdin = true;
  few.Seconds = 60;
  const Outcome r = RunMcxray({ "render", BadSLC, "--samples", "1023", "--output", output }, few);
  ExpectOneLine(r, "could not be started", folder, output);
}

TEST(HostileProcess, OneProcessAllowedIsOneLine)
{
  if (MCXRAY_TEST_SANITIZED)
  {
    GTEST_SKIP() << "a process limit the sanitizers' runtimes cannot live under (the unsanitized "
                    "build runs it)";
  }
  // RLIMIT_NPROC binds only an unprivileged user: as root, the child runs
  // as nobody (the test's folder open to it).
  const std::string folder = Folder("process_one_process");
  ::chmod(folder.c_str(), 0777);
  const std::string output = folder + "/never.png";
  const std::string input = folder + "/bad.slc";
  vtksys::SystemTools::CopyAFile(BadSLC, input);
  ::chmod(input.c_str(), 0644);
  const pid_t child = ::fork();
  if (child == 0)
  {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0))
    {
      ::_exit(3);
    }
    const rlimit one = { 1, 1 };
    ::setrlimit(RLIMIT_NPROC, &one);
    const int errors = ::open((folder + "/stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(errors, STDERR_FILENO);
    const int quiet = ::open("/dev/null", O_WRONLY);
    ::dup2(quiet, STDOUT_FILENO);
    ::execl(MCXRAY_CLI, MCXRAY_CLI, "render", input.c_str(), "--samples", "1023", "--threads", "1",
      "--output", output.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
  {
    GTEST_SKIP() << "cannot become an unprivileged user";
  }
  Outcome r;
  r.Status = status;
  r.Errors = Slurp(folder + "/stderr.txt");
  ExpectOneLine(r, "", folder, output);
  EXPECT_EQ(std::string::npos, r.Errors.find("crashed")) << r.Errors; // never read at all
}

TEST(HostileProcess, AClosedPipeIsOneLineAndNoOutput)
{
  // mcxray render ... | true: SIGPIPE is ignored and the failed write to
  // stdout ends the run before any image is written.
  const std::string folder = Folder("process_pipe");
  const std::string output = folder + "/never.png";
  Conditions pipe;
  pipe.BrokenStdout = true;
  pipe.Seconds = 60;
  const Outcome r = RunMcxray({ "render", "--samples", "1023", "--output", output }, pipe);
  ExpectOneLine(r, "cannot write to standard output", folder, output);
}

TEST(HostileProcess, AClosedStdoutIsNotAFileToWriteInto)
{
  // mcxray render >&-: stdout is /dev/null, not the number of the next file
  // opened (the output's temporary would have received the log).
  const std::string folder = Folder("process_closed_stdout");
  const std::string output = folder + "/image.pfm";
  Conditions closed;
  closed.CloseStdout = true;
  closed.Seconds = 60;
  const Outcome r =
    RunMcxray({ "render", "--samples", "1023", "--size", "8x4", "--output", output }, closed);
  EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 0) << r.Status << "\n" << r.Errors;
  EXPECT_EQ("", r.Errors);
  // A PFM of 8 x 4 float32 pixels and its 3-line header, nothing else.
  EXPECT_EQ(0u, Slurp(output).find("Pf\n8 4\n-1.0\n")) << Slurp(output).substr(0, 40);
  EXPECT_EQ(std::string("Pf\n8 4\n-1.0\n").size() + 4 * 8 * 4, Slurp(output).size());
}

TEST(HostileProcess, TheCPUTimeLimitIsOneLine)
{
  // ulimit -t 2: SIGXCPU after two seconds of CPU time ends the run with
  // one line and exit status 2 (not a silent death), well before the hard
  // limit's SIGKILL.
  const std::string folder = Folder("process_cpu");
  const std::string output = folder + "/never.png";
  Conditions cpu;
  cpu.CPUSeconds = 2;
  cpu.Seconds = 60;
  const Outcome r =
    RunMcxray({ "render", "--samples", "68719476735", "--quiet", "--output", output }, cpu);
  ExpectOneLine(r, "CPU time limit", folder, output);
}

TEST(HostileProcess, SignalsDuringTheWriteLeaveNoTemporary)
{
  // Each catchable terminating signal, sent while the output's temporary
  // exists: one line, the temporary removed, and the signal's own end
  // (SIGXCPU: exit status 2; SIGPIPE is ignored: the image is written).
  for (int signal : { SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGTERM, SIGPIPE })
  {
    const std::string folder = Folder("process_signal_" + std::to_string(signal));
    const std::string output = folder + "/big.vti";
    Conditions during;
    during.Signal = signal;
    during.Folder = folder;
    during.SignalWhen = ".part-";
    during.Seconds = 120;
    const Outcome r = RunMcxray(
      { "render", "--samples", "1023", "--size", "2048x2048", "--quiet", "--output", output },
      during);
    ASSERT_TRUE(r.Signalled) << "no temporary seen for signal " << signal << "\n" << r.Errors;
    EXPECT_EQ(0, CountFiles(folder, ".part-")) << signal;
    if (signal == SIGPIPE)
    {
      EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 0) << r.Errors;
      EXPECT_TRUE(vtksys::SystemTools::FileExists(output));
      EXPECT_EQ("", r.Errors);
      continue;
    }
    EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << signal;
    EXPECT_EQ(1, Lines(r.Errors)) << signal << ": " << r.Errors;
    EXPECT_NE(std::string::npos, r.Errors.find("the unfinished output was removed"))
      << signal << ": " << r.Errors;
    if (signal == SIGXCPU)
    {
      EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 2) << r.Status;
    }
    else
    {
      EXPECT_TRUE(WIFSIGNALED(r.Status) && WTERMSIG(r.Status) == signal) << r.Status;
      EXPECT_NE(std::string::npos, r.Errors.find("interrupted by SIG")) << r.Errors;
    }
  }
}

TEST(HostileProcess, ASignalDuringASweepLeavesNoneOfItsImages)
{
  // Signalled while the second pose's image is written: the first, complete
  // and held until the run ends, goes with it. Nothing of the run is left.
  const std::string folder = Folder("process_sweep");
  Conditions during;
  during.Signal = SIGTERM;
  during.Folder = folder;
  during.SignalWhen = "_0001.pfm.part-";
  const Outcome r = RunMcxray(
    { "render", "--gantry", "0:90:3", "--detector", "2048x2048", "--samples", "1023", "--quiet",
      "--output", folder + "/sweep.pfm", "--output-geometry", folder + "/sweep.json" },
    during);
  ASSERT_TRUE(r.Signalled) << r.Errors;
  EXPECT_TRUE(WIFSIGNALED(r.Status) && WTERMSIG(r.Status) == SIGTERM) << r.Status;
  EXPECT_EQ(1, Lines(r.Errors)) << r.Errors;
  EXPECT_NE(std::string::npos, r.Errors.find("the unfinished output was removed")) << r.Errors;
  EXPECT_EQ(0, CountFiles(folder, "sweep")) << "files of the interrupted run are left";
  // Unsignalled, the run writes all three and the geometry.
  const Outcome whole = RunMcxray(
    { "render", "--gantry", "0:90:3", "--detector", "16x16", "--samples", "1023", "--quiet",
      "--output", folder + "/sweep.pfm", "--output-geometry", folder + "/sweep.json" },
    Conditions());
  EXPECT_TRUE(WIFEXITED(whole.Status) && WEXITSTATUS(whole.Status) == 0) << whole.Errors;
  EXPECT_EQ(4, CountFiles(folder, "sweep"));
  EXPECT_EQ(0, CountFiles(folder, ".part-"));
}

TEST(HostileProcess, OptionsThatWouldRunWithoutEndAreOneLine)
{
  const std::string folder = Folder("process_options");
  const std::string output = folder + "/never.png";
  // More threads than TBB may use (its own two-line warning before).
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  ExpectOneLine(
    RunMcxray({ "render", "--threads", std::to_string(std::max(cores, 1) + 1), "--output", output },
      Conditions()),
    "--threads", folder, output);
  // 2^63 - 1 samples would run for centuries, --quiet or not.
  for (const char* quiet : { "--quiet", "--seed" })
  {
    std::vector<std::string> arguments = { "render", "--samples", "9223372036854775807", quiet,
      "--output", output };
    if (std::string(quiet) == "--seed")
    {
      arguments.insert(arguments.begin() + 4, "1");
    }
    ExpectOneLine(RunMcxray(arguments, Conditions()), "2^40 - 1", folder, output);
  }
  // 2^40 samples are refused, 2^40 - 1 are not (announced, then stopped).
  ExpectOneLine(RunMcxray({ "render", "--samples", "1099511627776", "--quiet", "--output", output },
                  Conditions()),
    "2^40 - 1", folder, output);
  // An empty input path is refused, not read as "no input" (the bundled CT).
  ExpectOneLine(RunMcxray({ "render", "", "--output", output }, Conditions()),
    "the input path is empty", folder, output);
}

TEST(HostileProcess, LongOutputNamesAreRefusedBeforeTheRender)
{
  // A name of 245 to 255 bytes fits the file system, its temporary
  // (NAME.part-PID.png, 11 bytes longer at least) does not: refused up
  // front, in a second (from 241 bytes, as the process id's digits make it).
  const std::string folder = Folder("process_long_name");
  for (std::size_t length : { 245, 250, 255, 256 })
  {
    const std::string output = folder + "/" + std::string(length - 4, 'a') + ".png";
    const Outcome r =
      RunMcxray({ "render", "--samples", "1023", "--output", output }, Conditions());
    ExpectOneLine(r, "too long", folder, output);
    EXPECT_LT(r.Seconds, 5.0) << length;
  }
  // A name whose temporary fits is written.
  const std::string fits = folder + "/" + std::string(200, 'b') + ".png";
  const Outcome r =
    RunMcxray({ "render", "--samples", "1023", "--quiet", "--output", fits }, Conditions());
  EXPECT_TRUE(WIFEXITED(r.Status) && WEXITSTATUS(r.Status) == 0) << r.Errors;
  EXPECT_TRUE(vtksys::SystemTools::FileExists(fits));
}

TEST(HostileProcess, AnUnreadableInputSaysWhy)
{
  // errno's words through the CLI, one line (as root every file is
  // readable: the child drops to nobody).
  const std::string folder = Folder("process_unreadable");
  ::chmod(folder.c_str(), 0777);
  const std::string input = folder + "/locked.vti";
  vtksys::SystemTools::CopyAFile(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti", input);
  ::chmod(input.c_str(), 0000);
  const std::string output = folder + "/never.png";
  const pid_t child = ::fork();
  if (child == 0)
  {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0))
    {
      ::_exit(3);
    }
    const int errors = ::open((folder + "/stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(errors, STDERR_FILENO);
    const int quiet = ::open("/dev/null", O_WRONLY);
    ::dup2(quiet, STDOUT_FILENO);
    ::execl(MCXRAY_CLI, MCXRAY_CLI, "render", input.c_str(), "--samples", "1023", "--output",
      output.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
  {
    GTEST_SKIP() << "cannot become an unprivileged user";
  }
  Outcome r;
  r.Status = status;
  r.Errors = Slurp(folder + "/stderr.txt");
  ExpectOneLine(r, "permission denied", folder, output);
}

TEST(HostileProcess, AWarningBeforeAnErrorIsNotPrinted)
{
  // A NaN voxel's warning, then an error (a budget too small for the
  // image): one line, the error.
  const std::string folder = Folder("process_warning_then_error");
  const std::string input = folder + "/nan.vti";
  const int dims[3] = { 8, 8, 8 };
  auto volume = mcxtest::MakeVolume(VTK_FLOAT, dims,
    [](int i, int j, int k) { return i == 3 && j == 3 && k == 3 ? std::nan("") : i + j + k; });
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(input.c_str());
  ASSERT_EQ(1, writer->Write());
  const std::string output = folder + "/never.png";
  const Outcome r = RunMcxray({ "render", input, "--samples", "1023", "--size", "8192x8192",
                                "--memory-limit", "64M", "--output", output },
    Conditions());
  ExpectOneLine(r, "memory budget", folder, output);
  EXPECT_EQ(std::string::npos, r.Errors.find("warning")) << r.Errors;
}
