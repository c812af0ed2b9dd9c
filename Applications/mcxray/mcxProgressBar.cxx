#include "mcxProgressBar.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"

#include <cstdio>
#include <string>

#ifdef _WIN32
#include <io.h>
#else
#include <unistd.h>
#endif

namespace mcxapp
{

namespace
{
// kwsys has no public terminal test, hence the one platform switch here.
bool IsTerminal(std::FILE* stream)
{
#ifdef _WIN32
  return _isatty(_fileno(stream)) != 0;
#else
  return isatty(fileno(stream)) != 0;
#endif
}
}

ProgressBar::ProgressBar()
{
  this->Enabled = IsTerminal(stderr);
  this->Command->SetClientData(this);
  this->Command->SetCallback(&ProgressBar::OnProgress);
}

ProgressBar::~ProgressBar() = default;

void ProgressBar::Watch(vtkAlgorithm* algorithm)
{
  algorithm->AddObserver(vtkCommand::ProgressEvent, this->Command);
}

void ProgressBar::Begin(const std::string& stage, std::size_t part, std::size_t parts)
{
  this->Stage = stage;
  this->Part = part;
  this->Parts = parts > 0 ? parts : 1;
  if (part == 0)
  {
    this->Start = std::chrono::steady_clock::now();
  }
  this->Shown = false;
}

void ProgressBar::End()
{
  if (this->Shown)
  {
    std::fprintf(stderr, "\r%s\r", std::string(70, ' ').c_str());
    std::fflush(stderr);
  }
}

void ProgressBar::OnProgress(vtkObject*, unsigned long, void* self, void* fraction)
{
  static_cast<ProgressBar*>(self)->Update(*static_cast<double*>(fraction));
}

// Half a second of silence first: short stages never show a bar.
void ProgressBar::Update(double fraction)
{
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  if (!this->Enabled || elapsed < 0.5)
  {
    return;
  }
  fraction = (this->Part + fraction) / this->Parts;
  const int width = 40;
  const int filled = static_cast<int>(fraction * width);
  std::fprintf(stderr, "\r%-12s [%s%s] %3d%%", this->Stage.c_str(),
    std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
    static_cast<int>(fraction * 100));
  std::fflush(stderr);
  this->Shown = true;
}

} // namespace mcxapp
