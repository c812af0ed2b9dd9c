#include "vtkMCXIndexProjectionPrivate.h"

#include "mcxChannelSplit.h"
#include "mcxEveryVoxelSource.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXChannelFractionsPrivate.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXProjectionPrivate.h"
#include "vtkMCXProjector.h"

#include "vtkCommunicator.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{
using mcx::Accumulator;
using mcx::CollectSums;
using mcx::Projection;
using mcx::RandomPartsOf;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Stage 1b: samples generated from the index and deposited as they come,
// never stored. Under a controller of several processes the index is this
// process's piece: it deposits the samples whose voxels it holds, and the
// processes add their sums, so that every one holds the single-process image.
class IndexProjection
{
public:
  IndexProjection(vtkAlgorithm* self, const mcx::ProjectionGeometry& geometry,
    vtkMultiProcessController* controller, const int wholeExtent[6])
    : Self(self)
    , Geometry(geometry)
    , Controller(mcx::IsDistributed(controller) ? controller : nullptr)
  {
    std::copy(wholeExtent, wholeExtent + 6, this->WholeExtent);
  }

  /// Reads the index and evaluates the TF; false (reported) when no image
  /// can be made (on every process, when distributed).
  bool Prepare(vtkImageData* index, vtkPiecewiseFunction* tf)
  {
    const bool prepared = this->Controller
      ? mcx::PrepareDistributedSampling(this->Self, "project", index, tf, this->Controller,
          this->WholeExtent, this->Levels, this->View, this->Table, this->Integral)
      : mcx::PrepareSampling(
          this->Self, "project", index, tf, this->View, this->Table, this->Integral);
    if (prepared && (this->EveryVoxel || this->ChoosesDeposit))
    {
      this->WeighEveryVoxel(tf);
    }
    return prepared;
  }

  bool IsEmpty() const { return this->Table.IsEmpty(); }

  /// Splits every deposit into `self`'s channels by its level's fractions
  /// (mcx::ChannelFractionTable); false (reported) when they do not fit the
  /// index. Call it after Prepare.
  bool SplitIntoChannels(vtkMCXProjector* self, vtkPiecewiseFunction* tf)
  {
    this->Channels = self->GetNumberOfChannels();
    if (this->Channels == 0)
    {
      return true;
    }
    std::vector<std::uint64_t> fractions;
    std::string problem = mcx::ChannelFractionTable(self, this->View, tf, fractions);
    if (this->Controller)
    {
      // Every process stops together, as when preparing.
      problem = mcx::FirstErrorOfAll(this->Controller, problem);
    }
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(this->Self, "Cannot project into channels: " << problem << ".");
      return false;
    }
    this->Shares.Build(fractions, this->Channels);
    return true;
  }

  /// Voxels of non-zero weight in the whole volume (after Prepare, with
  /// EveryVoxel or ChoosesDeposit).
  std::int64_t KeptVoxels() const { return this->KeptVoxelCount; }

  /// The image of 2^m - 1 samples, progress running from progressBegin to
  /// progressEnd. Given `prefix`, this projector's image of fewer samples
  /// (2^j - 1, j < m, the same deposit), only the samples after them are
  /// drawn and its sums added: the same image, bit for bit, as all 2^m - 1
  /// drawn (SampleSource::FirstSample), so that a target's pilot and
  /// re-checks are not paid twice.
  Projection Project(
    unsigned m, double progressBegin, double progressEnd, const Projection* prefix = nullptr) const
  {
    Projection projection;
    projection.Count = mcx::SampleCount(m);
    const int strategy =
      this->EveryVoxel ? vtkMCXTypes::EVERY_VOXEL : static_cast<int>(this->Method);
    if (prefix &&
      (prefix->Count >= projection.Count || prefix->EveryVoxel ||
        prefix->Deposit != static_cast<int>(this->DepositMode) || prefix->Strategy != strategy))
    {
      prefix = nullptr;
    }
    projection.Integral = this->Integral;
    projection.SampleWeight =
      projection.Count > 0 ? this->Integral / static_cast<double>(projection.Count) : 0.0;
    this->Run(projection,
      [&](Accumulator& accumulator)
      {
        accumulator.SetSplit(mcx::FirstHalfSize(projection.Count));
        if (m == 0)
        {
          return true;
        }
        const std::uint64_t first = prefix ? prefix->Count : 0;
        projection.Drawn = projection.Count - first;
        return this->View.WideIds
          ? this->Generate<std::uint64_t>(m, first, accumulator, progressBegin, progressEnd)
          : this->Generate<std::uint32_t>(m, first, accumulator, progressBegin, progressEnd);
      });
    if (prefix && projection.Completed && prefix->Sums.size() == projection.Sums.size())
    {
      // The prefix's samples are all in the first Halton half of the longer run.
      AddAsFirstHalf(prefix->Sums, projection.Sums);
      for (std::size_t c = 0; c < projection.ChannelSums.size(); ++c)
      {
        AddAsFirstHalf(prefix->ChannelSums[c], projection.ChannelSums[c]);
      }
    }
    return projection;
  }

  /// The image of every voxel of non-zero weight once (EveryVoxel), each
  /// weighted by its level's weight over the mean: the points carry the
  /// integral together, as a stored every-voxel cloud's do.
  Projection ProjectEveryVoxel() const
  {
    Projection projection;
    projection.EveryVoxel = true;
    projection.Count = static_cast<std::uint64_t>(this->KeptVoxelCount);
    projection.Integral = this->Integral;
    // The weights' sum over the whole volume, each weight rounded to fixed
    // point as the deposits take it (summed in double: the same on every
    // process), in counts.
    double carried = 0.0;
    for (std::int64_t l = 0; l < this->View.NumberOfLevels; ++l)
    {
      carried += static_cast<double>(this->View.LevelOffsets[l + 1] - this->View.LevelOffsets[l]) *
        mcx::ToDouble(mcx::FixedIncrement(this->LevelWeights[static_cast<std::size_t>(l)]));
    }
    carried /= mcx::FixedOne;
    projection.SampleWeight = carried > 0 ? this->Integral / carried : 0.0;
    this->Run(projection,
      [&](Accumulator& accumulator)
      {
        return this->View.WideIds ? this->DepositEveryVoxel<std::uint64_t>(accumulator)
                                  : this->DepositEveryVoxel<std::uint32_t>(accumulator);
      });
    return projection;
  }

  mcx::Strategy Method =
    mcx::Strategy::Hybrid; // with EveryVoxel: Hybrid, which no voxel choice uses
  bool EveryVoxel = false; // vtkMCXTypes::EVERY_VOXEL instead of Method (set before Prepare)
  bool ChoosesDeposit =
    false; // a target's choice, every voxel once among them (set before Prepare)
  mcx::Kernel Reconstruction = mcx::Kernel::Tent;
  std::uint64_t Seed = 0;
  mcx::Deposit DepositMode = mcx::Deposit::Point;
  double FootprintReach = 16.0;

private:
  // Adds a shorter run's sums (all of them) to a longer run's all and first half.
  static void AddAsFirstHalf(
    const std::vector<mcx::FixedSum>& prefix, std::vector<mcx::FixedSum>& sums)
  {
    const std::size_t pixels = sums.size() / 2;
    for (std::size_t p = 0; p < pixels && prefix.size() == sums.size(); ++p)
    {
      sums[p] += prefix[p];
      sums[pixels + p] += prefix[p];
    }
  }

  // The channel shares of a sample in `level` (null without channels).
  const mcx::ChannelShares* SharesOf(std::int64_t level) const
  {
    return this->Channels > 0 ? this->Shares.Of(level) : nullptr;
  }

  // Deposits into a new accumulator for the view, then collects the sums
  // into the projection (added over the processes when distributed).
  template <typename Deposit>
  void Run(Projection& projection, Deposit&& deposit) const
  {
    const auto start = std::chrono::steady_clock::now();
    Accumulator accumulator;
    double origin[3], matrix[9];
    this->View.SourceToWorld(origin, matrix);
    const mcx::DepositSettings settings = this->Settings();
    accumulator.Reset(this->Geometry, origin, matrix, std::vector<double>(), settings);
    accumulator.SetChannels(this->Channels);
    projection.FallsAsInverseM = accumulator.ErrorFallsAsInverseM();
    projection.RandomParts = RandomPartsOf(accumulator, settings, this->FootprintReach);
    projection.Deposit = static_cast<int>(this->DepositMode);
    projection.Strategy =
      this->EveryVoxel ? vtkMCXTypes::EVERY_VOXEL : static_cast<int>(this->Method);
    std::string error;
    try
    {
      const auto depositStart = std::chrono::steady_clock::now();
      projection.Completed = deposit(accumulator);
      projection.DepositSeconds = SecondsSince(depositStart);
      CollectSums(accumulator, projection);
    }
    catch (const std::bad_alloc&)
    {
      error = "out of memory projecting into " + std::to_string(this->Geometry.Size[0]) + " x " +
        std::to_string(this->Geometry.Size[1]) + " pixels" +
        (this->Channels > 0 ? " and " + std::to_string(this->Channels) + " channels" : "");
    }
    if (this->Controller)
    {
      // Every process reaches this point, whatever happened to it; an abort
      // on any process leaves the image incomplete on all.
      error = mcx::FirstErrorOfAll(this->Controller, error);
      if (error.empty())
      {
        const int completed = projection.Completed ? 1 : 0;
        int everywhere = 0;
        this->Controller->AllReduce(&completed, &everywhere, 1, vtkCommunicator::MIN_OP);
        projection.Completed = everywhere == 1;
        if (projection.Completed)
        {
          mcx::SumExactly(this->Controller, projection.Sums);
          for (std::vector<mcx::FixedSum>& channel : projection.ChannelSums)
          {
            mcx::SumExactly(this->Controller, channel);
          }
        }
      }
    }
    if (!error.empty())
    {
      throw std::runtime_error(error);
    }
    projection.FixedSeconds = SecondsSince(start) - projection.DepositSeconds;
    if (this->Controller)
    {
      // The slowest process's times, so that every process makes the same choice with them.
      const double mine[2] = { projection.DepositSeconds, projection.FixedSeconds };
      double slowest[2] = { 0, 0 };
      this->Controller->AllReduce(mine, slowest, 2, vtkCommunicator::MAX_OP);
      projection.DepositSeconds = slowest[0];
      projection.FixedSeconds = slowest[1];
    }
  }

  // Each level's every-voxel weight (the TF's over the mean of the kept
  // voxels', 0 for a level kept out) and the whole volume's kept voxels.
  void WeighEveryVoxel(vtkPiecewiseFunction* tf)
  {
    std::vector<double> weights = this->View.EvaluateTransferFunction(tf);
    std::vector<char> kept;
    this->KeptVoxelCount = this->View.KeepLevels(weights, kept);
    const double total = this->Table.WeightSum();
    this->LevelWeights.assign(weights.size(), 0.0);
    for (std::size_t l = 0; l < weights.size(); ++l)
    {
      this->LevelWeights[l] = kept[l]
        ? mcx::EveryVoxelWeight(weights[l], static_cast<double>(this->KeptVoxelCount), total)
        : 0.0;
    }
  }

  // This process's kept voxels, each deposited once (ProjectEveryVoxel).
  template <typename IdType>
  bool DepositEveryVoxel(Accumulator& accumulator) const
  {
    mcx::EveryVoxelSource<IdType> source;
    source.SortedIds = this->View.IdPointer<IdType>();
    source.LevelOffsets =
      this->View.PieceOffsets ? this->View.PieceOffsets : this->View.LevelOffsets;
    source.NumberOfLevels = this->View.NumberOfLevels;
    source.LevelWeights = this->LevelWeights.data();
    source.Decoder = mcx::VoxelDecoder<IdType>(static_cast<std::uint64_t>(this->View.Dimensions[0]),
      static_cast<std::uint64_t>(this->View.Dimensions[1]));
    std::copy(this->View.PieceStart, this->View.PieceStart + 3, source.PieceStart);
    for (int a = 0; a < 2; ++a)
    {
      source.WholeDimensions[a] =
        static_cast<std::uint64_t>(this->View.Extent[2 * a + 1] - this->View.Extent[2 * a] + 1);
    }
    source.Reconstruction = this->Reconstruction;
    source.Centres = this->DepositMode == mcx::Deposit::Footprint;
    source.Seed = this->Seed;
    source.Prepare();
    accumulator.SetSplit(0); // no halves: nothing to estimate
    return mcx::BatchedFor(this->Self, source.Size(), 0.0, 1.0,
      [&](std::uint64_t b, std::uint64_t e)
      {
        const Accumulator::ThreadImage image = accumulator.Local();
        if (this->DepositMode == mcx::Deposit::Footprint)
        {
          mcx::FootprintBatch footprints(image);
          source.Generate(b, e,
            [&](std::uint64_t k, const double p[3], double weight, std::int64_t level)
            { footprints.Add(k, p, weight, this->SharesOf(level)); });
          footprints.Flush();
        }
        else
        {
          source.Generate(b, e,
            [&](std::uint64_t k, const double p[3], double weight, std::int64_t level)
            { image.DepositPoint(k, p, weight, this->SharesOf(level)); });
        }
      });
  }

  // The deposit, with the support's depth range (perspective footprints).
  mcx::DepositSettings Settings() const
  {
    mcx::DepositSettings settings;
    settings.Mode = this->DepositMode;
    settings.Reconstruction = this->Reconstruction;
    settings.Seed = this->Seed;
    settings.Reach = this->FootprintReach;
    settings.Stratified = this->Method != mcx::Strategy::MonteCarlo;
    settings.TableMemory = mcx::MemoryBudget(); // beyond: the projector's "Cannot project" error
    double corners[24];
    mcx::ComputeSupportCorners(this->View.Extent, this->View.Origin, this->View.Spacing,
      this->View.Direction, mcx::KernelRadius(this->Reconstruction), corners);
    mcx::SupportDepthRange(this->Geometry, corners, settings.Depths);
    return settings;
  }

  template <typename IdType>
  bool Generate(unsigned m, std::uint64_t firstSample, Accumulator& accumulator,
    double progressBegin, double progressEnd) const
  {
    mcx::SampleSource<IdType> source = this->View.MakeSource<IdType>(this->Table);
    source.Method = this->Method;
    source.Reconstruction = this->Reconstruction;
    source.Seed = this->Seed;
    source.Exponent = m;
    source.FirstSample = firstSample;
    source.Centres = this->DepositMode == mcx::Deposit::Footprint;
    // The runs of sample ranks this piece deposits (all of them for a whole
    // index), laid end to end.
    const auto runs = source.PieceRanks();
    std::vector<std::uint64_t> ends(runs.size());
    std::uint64_t total = 0;
    for (std::size_t r = 0; r < runs.size(); ++r)
    {
      total += runs[r].second - runs[r].first;
      ends[r] = total;
    }
    return mcx::BatchedFor(this->Self, total, progressBegin, progressEnd,
      [&](std::uint64_t b, std::uint64_t e)
      {
        const Accumulator::ThreadImage image = accumulator.Local();
        // This chunk's runs of ranks, each sample handed to `deposit`.
        auto generate = [&](auto& deposit)
        {
          std::size_t r =
            static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), b) - ends.begin());
          for (; r < runs.size() && b < e; ++r)
          {
            const std::uint64_t runBegin = ends[r] - (runs[r].second - runs[r].first);
            const std::uint64_t stop = std::min(e, ends[r]);
            source.Generate(
              runs[r].first + (b - runBegin), runs[r].first + (stop - runBegin), deposit);
            b = stop;
          }
        };
        // Points of perspective views are projected a batch at a time, on
        // SIMD lanes: their division and square root pay for the batch's
        // stores and loads, a parallel view's few products do not.
        // Footprints go in batches in either view (FootprintBatch). Each
        // deposit gets a loop of its own. Split into channels, each
        // sample's shares are its level's.
        const bool footprint = this->DepositMode == mcx::Deposit::Footprint;
        const bool batched = !footprint && this->Geometry.Perspective;
        if (footprint)
        {
          mcx::FootprintBatch footprints(image);
          auto batch = [&](std::uint64_t k, const double p[3], double, std::int64_t level)
          { footprints.Add(k, p, 1.0, this->SharesOf(level)); };
          generate(batch);
          footprints.Flush();
        }
        else if (batched && this->Channels > 0)
        {
          Accumulator::ThreadImage::PointBatch points(image);
          auto batch = [&](std::uint64_t k, const double p[3], double, std::int64_t level)
          { points.Add(k, p, this->SharesOf(level)); };
          generate(batch);
          points.Flush();
        }
        else if (batched)
        {
          Accumulator::ThreadImage::PointBatch points(image);
          auto batch = [&](std::uint64_t k, const double p[3]) { points.Add(k, p); };
          generate(batch);
          points.Flush();
        }
        else if (this->Channels > 0)
        {
          auto deposit = [&](std::uint64_t k, const double p[3], double, std::int64_t level)
          { image.DepositPoint(k, p, 1.0, this->SharesOf(level)); };
          generate(deposit);
        }
        else
        {
          auto deposit = [&](std::uint64_t k, const double p[3]) { image.DepositPoint(k, p); };
          generate(deposit);
        }
      });
  }

  vtkAlgorithm* Self;
  const mcx::ProjectionGeometry& Geometry;
  vtkMultiProcessController* Controller;
  int WholeExtent[6];
  mcx::DistributedLevels Levels;
  mcx::IndexView View;
  mcx::TransferTable Table;
  double Integral = 0.0;
  std::vector<double> LevelWeights; // per level, with EveryVoxel
  std::int64_t KeptVoxelCount = 0;  // in the whole volume, with EveryVoxel
  int Channels = 0;                 // the deposit's split (SplitIntoChannels)
  mcx::ChannelShareTable Shares;    // per level
};

// The sample count a target asks for, measured on a projection whose
// error falls as M^-decay.
double SamplesNeeded(
  const Projection& projection, double targetError, int targetLevels, double decay)
{
  double needed = 0.0;
  if (targetError > 0)
  {
    const double ratio = projection.EstimatedError() / targetError;
    needed = std::max(needed, static_cast<double>(projection.Count) * std::pow(ratio, 1.0 / decay));
  }
  if (targetLevels > 0)
  {
    needed = std::max(needed, mcx::QuantizationSampleCount(projection.Sums, targetLevels));
  }
  return needed;
}

// The pilot run's exponent: about 4 samples per pixel, within
// [PilotSampleExponent, maximumExponent].
unsigned PilotExponent(const mcx::ProjectionGeometry& geometry, unsigned maximumExponent)
{
  const long long pixels = static_cast<long long>(geometry.Size[0]) * geometry.Size[1];
  return std::min(maximumExponent,
    std::max(static_cast<unsigned>(vtkMCXTypes::PilotSampleExponent),
      mcx::ExponentForSampleCount(4 * pixels)));
}

// Stage 2 (target controls): from a pilot run of 2^m - 1 samples that
// measured the image, the sample count is scaled to meet the target and
// re-checked on the larger run (up to three times), within [pilot,
// maximumExponent].
Projection RefineToTarget(const IndexProjection& sampler, Projection projection, unsigned m,
  double decay, double targetError, int targetLevels, unsigned maximumExponent,
  double progressStart)
{
  const double passEnd[] = { 0.8, 0.95, 1.0 };
  for (int pass = 0; pass < 3 && projection.Completed; ++pass)
  {
    const double needed = SamplesNeeded(projection, targetError, targetLevels, decay);
    const unsigned next = std::min(maximumExponent,
      mcx::ExponentForSampleCount(static_cast<long long>(std::min(needed, 9.0e18))));
    if (next <= m)
    {
      break;
    }
    m = next;
    projection =
      sampler.Project(m, pass == 0 ? progressStart : passEnd[pass - 1], passEnd[pass], &projection);
  }
  return projection;
}

Projection ProjectToTarget(const IndexProjection& sampler, const mcx::ProjectionGeometry& geometry,
  double targetError, int targetLevels, unsigned maximumExponent)
{
  const unsigned m = PilotExponent(geometry, maximumExponent);
  Projection pilot = sampler.Project(m, 0.0, 0.05);
  const double decay = mcx::ErrorDecayExponent(pilot.FallsAsInverseM);
  return RefineToTarget(
    sampler, std::move(pilot), m, decay, targetError, targetLevels, maximumExponent, 0.05);
}

// Seconds a deposit would take to go on from its pilot to `samples`
// (those the pilot drew are kept: Project's prefix), extrapolated from the
// pilot: the fixed part (the view's tables, the sums' collection) once, the
// deposits' part in proportion to the samples left to draw.
double SecondsPerSample(const Projection& pilot)
{
  return pilot.DepositSeconds / std::max<double>(1.0, static_cast<double>(pilot.Drawn));
}

double PredictedSeconds(const Projection& pilot, double samples)
{
  return pilot.FixedSeconds +
    SecondsPerSample(pilot) * std::max(0.0, samples - static_cast<double>(pilot.Count));
}

// The exponent a of a deposit's error, falling as M^-a, measured between
// two pilots: a footprint's error falls as M^-1 only where voxels project
// to a pixel or more (on a CT of voxels 6 times smaller than its pixels it
// falls as M^-1/2, as a point deposit's does). Within [1/2, the deposit's
// own exponent].
double MeasuredDecay(const Projection& small, const Projection& large)
{
  const double nominal = mcx::ErrorDecayExponent(large.FallsAsInverseM);
  if (!(small.EstimatedError() > 0) || !(large.EstimatedError() > 0) || large.Count <= small.Count)
  {
    return nominal;
  }
  const double decay = std::log(small.EstimatedError() / large.EstimatedError()) /
    std::log(static_cast<double>(large.Count) / static_cast<double>(small.Count));
  return std::max(0.5, std::min(nominal, decay));
}

// Seconds a deposit would take from its pilot to the target, its error
// falling as M^-decay (capped at the largest count).
double SecondsToTarget(const Projection& pilot, double decay, double targetError, int targetLevels,
  unsigned maximumExponent)
{
  const double needed = std::min(SamplesNeeded(pilot, targetError, targetLevels, decay),
    static_cast<double>(mcx::SampleCount(maximumExponent)));
  return PredictedSeconds(pilot, needed);
}

// Stage 2 choosing the deposit (ChooseDepositForTarget): a pilot of each
// deposit (about 4 samples a pixel) measures its error and time. The point
// deposit's error falls as M^-1/2; the footprint's as M^-1 only where
// voxels cover a pixel or more, else as M^-1/2. When the footprint wins
// (or loses) under either law, that decides; in between a second footprint
// pilot of 4 times the samples measures how fast its error falls. The
// deposit predicted to reach the target soonest is refined from its pilot,
// whose samples it keeps (only the other deposit's pilot is spent). Every
// voxel once competes as well (relative error targets): it is the
// footprint deposit of every voxel, so its error is taken as the
// footprint's extrapolated to that many samples (an upper bound: it has no
// sampling noise) and its time as that many footprints.
Projection ChooseAndProjectToTarget(IndexProjection& sampler,
  const mcx::ProjectionGeometry& geometry, double targetError, int targetLevels,
  unsigned maximumExponent)
{
  const unsigned small = PilotExponent(geometry, maximumExponent);
  const mcx::Deposit modes[2] = { mcx::Deposit::Point, mcx::Deposit::Footprint };
  Projection pilots[2];
  for (int d = 0; d < 2; ++d)
  {
    sampler.DepositMode = modes[d];
    pilots[d] = sampler.Project(small, 0.02 * d, 0.02 * (d + 1));
    if (!pilots[d].Completed)
    {
      return std::move(pilots[d]);
    }
  }
  double decays[2] = { mcx::ErrorDecayExponent(pilots[0].FallsAsInverseM),
    mcx::ErrorDecayExponent(pilots[1].FallsAsInverseM) };
  double seconds[2];
  seconds[0] = SecondsToTarget(pilots[0], decays[0], targetError, targetLevels, maximumExponent);
  seconds[1] = SecondsToTarget(pilots[1], decays[1], targetError, targetLevels, maximumExponent);
  const double slowest =
    SecondsToTarget(pilots[1], 0.5, targetError, targetLevels, maximumExponent);
  unsigned m = small;
  if (seconds[1] < seconds[0] && slowest > seconds[0] && small < maximumExponent)
  {
    sampler.DepositMode = mcx::Deposit::Footprint;
    m = std::min(maximumExponent, small + 2);
    Projection first = std::move(pilots[1]);
    pilots[1] = sampler.Project(m, 0.04, 0.08, &first);
    if (!pilots[1].Completed)
    {
      return std::move(pilots[1]);
    }
    decays[1] = MeasuredDecay(first, pilots[1]);
    seconds[1] = SecondsToTarget(pilots[1], decays[1], targetError, targetLevels, maximumExponent);
  }
  const int best = seconds[1] < seconds[0] ? 1 : 0;
  const double voxels = static_cast<double>(sampler.KeptVoxels());
  if (targetLevels == 0 && voxels > 0 && pilots[1].Count > 0)
  {
    const double everyVoxelError = pilots[1].EstimatedError() *
      std::pow(static_cast<double>(pilots[1].Count) / voxels, decays[1]);
    const double everyVoxelSeconds = pilots[1].FixedSeconds + SecondsPerSample(pilots[1]) * voxels;
    if (everyVoxelError <= targetError && everyVoxelSeconds < seconds[best])
    {
      sampler.DepositMode = mcx::Deposit::Footprint;
      sampler.EveryVoxel = true;
      return sampler.ProjectEveryVoxel();
    }
  }
  // Refined as a fixed deposit is, with its nominal exponent: the measured
  // one, from errors of 4 and 16 samples a pixel, can be lower than the
  // asymptote and overshoot the count (the re-checks catch a shortfall).
  sampler.DepositMode = modes[best];
  const double decay = mcx::ErrorDecayExponent(pilots[best].FallsAsInverseM);
  return RefineToTarget(sampler, std::move(pilots[best]), best == 1 ? m : small, decay, targetError,
    targetLevels, maximumExponent, 0.08);
}
}

namespace mcx
{
bool ProjectIndex(vtkMCXProjector* self, vtkImageData* index, const int wholeExtent[6],
  const mcx::ProjectionGeometry& geometry, Projection& projection)
{
  const bool targeted =
    self->GetTargetRelativeError() > 0 || self->GetTargetQuantizationLevels() > 0;
  IndexProjection sampler(self, geometry, self->GetController(), wholeExtent);
  sampler.EveryVoxel = self->GetStrategy() == vtkMCXTypes::EVERY_VOXEL;
  if (sampler.EveryVoxel && targeted)
  {
    vtkErrorWithObjectMacro(self,
      "Cannot project: every voxel is taken once (Strategy EVERY_VOXEL), so there is no sample "
      "count for TargetRelativeError or TargetQuantizationLevels to choose; set them to 0.");
    return false;
  }
  sampler.Method =
    sampler.EveryVoxel ? mcx::Strategy::Hybrid : static_cast<mcx::Strategy>(self->GetStrategy());
  sampler.Reconstruction = static_cast<mcx::Kernel>(self->GetKernel());
  sampler.Seed = static_cast<std::uint64_t>(self->GetSeed());
  sampler.DepositMode = static_cast<mcx::Deposit>(self->GetDeposit());
  sampler.FootprintReach = self->GetFootprintReach();
  sampler.ChoosesDeposit = targeted && self->GetChooseDepositForTarget();
  if (!sampler.Prepare(index, self->GetTransferFunction()) ||
    !sampler.SplitIntoChannels(self, self->GetTransferFunction()))
  {
    return false;
  }
  if (sampler.EveryVoxel)
  {
    projection = sampler.ProjectEveryVoxel();
    return true;
  }
  // Under a target SampleExponent is ignored (0 included).
  const unsigned m = sampler.IsEmpty() ? 0u : static_cast<unsigned>(self->GetSampleExponent());
  const double targetError = self->GetTargetRelativeError();
  const int targetLevels = self->GetTargetQuantizationLevels();
  const unsigned maximum = static_cast<unsigned>(self->GetMaximumSampleExponent());
  if (sampler.IsEmpty() || !targeted)
  {
    projection = sampler.Project(m, 0.0, 1.0);
  }
  else if (sampler.ChoosesDeposit)
  {
    projection = ChooseAndProjectToTarget(sampler, geometry, targetError, targetLevels, maximum);
  }
  else
  {
    projection = ProjectToTarget(sampler, geometry, targetError, targetLevels, maximum);
  }
  return true;
}
}
