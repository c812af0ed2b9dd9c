// Checks that need no data, made before any work so that a bad command
// line fails at once rather than after reading and indexing a volume.
#ifndef mcxPreflight_h
#define mcxPreflight_h

#include <string>

namespace mcxapp
{

/// Fails unless the directory that path would be written in exists and is
/// writable, and path, where it exists, is a regular file (a device, pipe
/// or socket would be replaced by the renamed image).
void CheckOutputDirectory(const std::string& path);

/// Fails if output names the input or one of its files (a DICOM series'
/// files, the data file of a .mhd or .nhdr header), by any path or link:
/// writing it would destroy the data being read.
void CheckOutputIsNotInput(
  const std::string& output, const std::string& input, const std::string& option);

/// Fails if spec is no transfer function, whatever the data.
void CheckTransferFunction(const std::string& spec);

} // namespace mcxapp

#endif
