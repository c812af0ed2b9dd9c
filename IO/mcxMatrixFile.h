// A file of projection matrices (mcxray render --projection-matrices): the
// JSON that --output-geometry writes (each pose's "P" and "size"), or plain
// text of 12 numbers per pose (row by row, separated by white space or
// commas; '#' starts a comment to the end of its line), in the layout of
// Core/mcxProjectionMatrix.h. Bounded: at most `limit` poses, 64 MiB, 64
// characters per number.
#ifndef mcxMatrixFile_h
#define mcxMatrixFile_h

#include <cstddef>
#include <string>
#include <vector>

namespace mcxio
{

struct MatrixPose
{
  double Matrix[12] = { 0 };
  bool HasSize = false; // JSON gives each pose's detector size; text does not
  int Size[2] = { 0, 0 };
};

/// The poses of the file at path. Returns "" or one line saying why not.
std::string ReadProjectionMatrices(
  const std::string& path, std::size_t limit, std::vector<MatrixPose>& poses);

} // namespace mcxio

#endif
