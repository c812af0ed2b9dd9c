// How samples become image sums (point or footprint, the kernel, the reach
// of a footprint, the depths its tables span): the settings the accumulator
// and the footprint ladder share, apart so that either can be read alone.
#ifndef mcxDepositSettings_h
#define mcxDepositSettings_h

#include "mcxFootprint.h"
#include "mcxSampleGenerator.h"

#include <algorithm>
#include <cstdint>

namespace mcx
{

/// How samples are deposited; the default is the paper's point deposit.
struct DepositSettings
{
  Deposit Mode = Deposit::Point;
  Kernel Reconstruction = Kernel::Tent;
  std::uint64_t Seed = 0; ///< of the footprint's random parts (its own stream)
  /// Pixels a deposited part may reach along each projected voxel axis
  /// (clamped to 0.5..32); a larger kernel is split (FootprintPlan), which
  /// bounds the cost of a sample.
  double Reach = 16.0;
  /// Perspective views: the depths (along the view, from the eye) between
  /// which the footprint is tabulated; samples nearer than Depths[0] are
  /// deposited as points.
  double Depths[2] = { 0.0, 0.0 };
  /// A voxel's edge vectors in the source frame (row-major, column k is
  /// edge k): the identity when samples come in voxel coordinates, the
  /// voxel's world edges for a stored cloud of world points.
  double VoxelMatrix[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  /// The bytes the footprint tables may take (FootprintLadder::Build throws
  /// std::runtime_error beyond them, before allocating); 0: no limit but
  /// the reach's (FootprintLadder::MaximumBytes). Not part of a view's key.
  double TableMemory = 0.0;
  /// Whether the voxel choice is stratified (Hybrid, QuasiMonteCarlo): only
  /// then does the footprint's error fall as about M^-1.
  bool Stratified = true;

  bool operator==(const DepositSettings& o) const
  {
    return this->Mode == o.Mode && this->Reconstruction == o.Reconstruction &&
      this->Seed == o.Seed && this->Reach == o.Reach && this->Depths[0] == o.Depths[0] &&
      this->Depths[1] == o.Depths[1] &&
      std::equal(this->VoxelMatrix, this->VoxelMatrix + 9, o.VoxelMatrix) &&
      this->Stratified == o.Stratified;
  }
  bool operator!=(const DepositSettings& o) const { return !(*this == o); }
};

} // namespace mcx

#endif
