// The one table of command-line options: each option's name, whether it
// takes a value, which commands accept it, and how it sets the Settings.
// Both commands parse their arguments through it. The help texts are kept
// whole in the commands (they group options and word them per command).
#ifndef mcxOptionTable_h
#define mcxOptionTable_h

namespace mcxapp
{

struct Settings;

enum class Command
{
  Render = 1,
  View = 2
};

/// The command's name, as typed after mcxray.
const char* CommandName(Command command);

/// Reads argv[2] .. argv[argc - 1] into settings for command, failing with
/// a one-line error on the first bad argument. Returns false when --help
/// (or -h) was asked for.
bool ParseArguments(int argc, char* argv[], Command command, Settings& settings);

} // namespace mcxapp

#endif
