// What both inputs of vtkMCXProjector make: the sums of one projection and
// the samples they came from (Projection), the accumulator they are
// deposited with, and what is random in a deposit. The index input
// (vtkMCXIndexProjectionPrivate) and the cloud input
// (vtkMCXCloudProjectionPrivate) fill a Projection; the projector writes it
// out as the image.
#ifndef vtkMCXProjectionPrivate_h
#define vtkMCXProjectionPrivate_h

#include "mcxControlImage.h"
#include "mcxErrorEstimate.h"
#include "mcxFixedPoint.h"
#include "mcxSampleAccumulator.h"
#include "vtkMCXSMPExecutor.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mcx
{
using Accumulator = mcx::SampleAccumulator<mcx::SMPExecutor>;

/// The sums of one projection (all samples in the first half of Sums, the
/// first Halton half in the second, as mcx::EstimateRelativeError reads them)
/// and the samples they came from.
struct Projection
{
  std::vector<mcx::FixedSum> Sums;
  // Per channel of a split deposit (vtkMCXProjector::SetNumberOfChannels),
  // laid out as Sums: their sums add up to Sums exactly.
  std::vector<std::vector<mcx::FixedSum>> ChannelSums;
  std::uint64_t Count = 0;
  double SampleWeight = 0.0;
  double Integral = 0.0;
  bool Completed = true;
  bool FallsAsInverseM = false; // see mcx::FootprintErrorCalibration
  bool EveryVoxel = false;      // not estimated: see mcx::IsEveryVoxelCloud
  // How an index input was projected (vtkMCXTypes' values; -1: a cloud's
  // own), and the run's wall-clock seconds: the deposits', and the rest
  // (the view's footprint tables, collecting the sums), what a target's
  // choice of deposit extrapolates.
  int Deposit = -1;
  int Strategy = -1;
  double DepositSeconds = 0.0;
  double FixedSeconds = 0.0;
  std::uint64_t Drawn = 0;      // the samples this run drew (Count less a prefix it extends)
  std::string RandomParts;      // the deposit's random parts, if any (RandomPartsOf)
  // A view-ordered cloud's control (mcx::CloudControlImage; empty: none):
  // H and its variance, the sums of the points counted once (as Sums), the
  // weight the points carry and that of the first half, and a pixel's beam
  // cross-section.
  std::vector<double> Control;
  double ControlVariance = 0.0;
  std::vector<mcx::FixedSum> OnceSums;
  double CarriedWeight = 0.0;
  double FirstHalfWeight = 0.0;
  double PixelArea = 1.0;

  mcx::ControlledSums Controlled() const
  {
    mcx::ControlledSums sums;
    sums.Pixels = this->Control.size();
    sums.Weighted = this->Sums.data();
    sums.Once = this->OnceSums.data();
    sums.Control = this->Control.data();
    sums.Count = this->Count;
    sums.CarriedWeight = this->CarriedWeight;
    sums.Integral = this->Integral;
    sums.PixelArea = this->PixelArea;
    sums.ControlVariance = this->ControlVariance;
    return sums;
  }

  /// Channel c's relative RMS error, estimated from its halves as the
  /// image's is (a control image is the total's alone).
  double ChannelEstimatedError(std::size_t c) const
  {
    if (this->EveryVoxel && this->Count > 0)
    {
      return std::nan("");
    }
    return (this->FallsAsInverseM ? mcx::FootprintErrorCalibration : 1.0) *
      mcx::EstimateRelativeError(this->ChannelSums[c], this->Count);
  }

  double EstimatedError() const
  {
    if (this->EveryVoxel && this->Count > 0) // an empty image is exactly known (0, below)
    {
      return std::nan("");
    }
    if (!this->Control.empty())
    {
      const std::size_t pixels = this->Control.size();
      return mcx::EstimateControlledRelativeError(this->Controlled(), this->Sums.data() + pixels,
        this->OnceSums.data() + pixels, this->FirstHalfWeight);
    }
    return (this->FallsAsInverseM ? mcx::FootprintErrorCalibration : 1.0) *
      mcx::EstimateRelativeError(this->Sums, this->Count);
  }
};

/// What is random in a deposit whose error does not fall as M^-1 (the
/// voxel choice aside): empty for whole footprints. An every-voxel image is
/// exact only without these.
std::string RandomPartsOf(
  const Accumulator& accumulator, const mcx::DepositSettings& settings, double footprintReach);

/// Collects the accumulator's sums into the projection's (Sums, and
/// OnceSums when controlled).
void CollectSums(Accumulator& accumulator, Projection& projection);
}

#endif
