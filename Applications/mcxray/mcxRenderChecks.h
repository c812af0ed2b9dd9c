// The checks of a render's command line made before any work: what one
// option allows depends on another, every file the run will write, and the
// cost of an absurd but valid sample count.
#ifndef mcxRenderChecks_h
#define mcxRenderChecks_h

namespace mcxapp
{

struct Settings;

/// Fails on options that contradict each other.
void CheckCombinations(const Settings& settings);

/// Fails unless every file the run writes (the output, a sweep's numbered
/// files, --output-geometry) can be written and is none of the input's.
void CheckOutputs(const Settings& settings);

/// Says on stderr (unless --quiet) what a very long run will cost.
void WarnOfLongRuns(const Settings& settings);

} // namespace mcxapp

#endif
