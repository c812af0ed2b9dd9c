// mcxray view: the interactive X-ray viewer of a volume, or one off-screen
// screenshot of it.
#ifndef mcxViewCommand_h
#define mcxViewCommand_h

namespace mcxapp
{

/// Runs `mcxray view ...`; returns the exit status.
int RunView(int argc, char* argv[]);

} // namespace mcxapp

#endif
