// mcxray render: one simulated X-ray image (a DRR) of a volume, written
// to a file, with a line per stage on stdout.
#ifndef mcxRenderCommand_h
#define mcxRenderCommand_h

namespace mcxapp
{

/// Prints the render help (the tool's main help) on stdout.
void PrintRenderUsage();

/// Runs `mcxray render ...`; returns the exit status.
int RunRender(int argc, char* argv[]);

} // namespace mcxapp

#endif
