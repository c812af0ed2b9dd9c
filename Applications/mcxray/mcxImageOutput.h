// Writes a LineIntegral image as .vti (float64 with geometry), .mha (float64), .png
// (windowed, 8 or 16 bit) or .pfm (float32), all or nothing: the file is
// written under a temporary name and renamed only when complete.
#ifndef mcxImageOutput_h
#define mcxImageOutput_h

#include <functional>
#include <string>

class vtkImageData;

namespace mcxapp
{

struct PngWindow
{
  bool Automatic = true; // 0 .. image maximum
  double Low = 0.0;
  double High = 1.0;
  int Bits = 8;
};

/// True when the extension is one the writer knows.
bool IsSupportedOutput(const std::string& path);

/// "" when the file name of path, and of the temporary it is written under
/// (NAME.part-PID.EXT), fit the file system's limit on a name (255 bytes on
/// most); else one line that says so, naming `option`. Checked before any
/// work, so that a long name does not fail after the render.
std::string OutputNameProblem(const std::string& path, const std::string& option);

/// beforeRename, if given, runs once the temporary is complete: a message
/// it returns fails the write (the temporary removed, path untouched).
using BeforeRename = std::function<std::string()>;
bool WriteImage(vtkImageData* image, const std::string& path, const PngWindow& window,
  std::string& error, const BeforeRename& beforeRename = BeforeRename());

/// Any file all or nothing, as the images: write(temporary) writes it whole
/// under the temporary name beside path, renamed to path only if write
/// returned true (and removed otherwise, or on a signal).
bool WriteFileAtomically(const std::string& path,
  const std::function<bool(const std::string&)>& write, std::string& error);

/// Writes an 8-bit RGB(A) image, a screenshot, as .png, all or nothing.
bool WriteScreenshot(vtkImageData* image, const std::string& path, std::string& error);

} // namespace mcxapp

#endif
