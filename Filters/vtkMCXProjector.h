/**
 * @class   vtkMCXProjector
 * @brief   Monte Carlo X-ray projection: counts samples per pixel.
 *
 * With a density index (vtkMCXDensityIndex) as input it generates the
 * samples and projects them at once, without storing them (the paper's
 * off-line rendering); with a point cloud from vtkMCXPointSampler it projects
 * the stored points. Accumulation is exact (integer counts, or fixed point
 * for perspective weights, in 128 bits), so the image is bit-identical for any
 * number of threads. See vtkMCXProjectorBase for the view and the output.
 *
 * The output's field data carries "SampleCount", "SampleWeight" and
 * "Integral" of the samples that made the image, and
 * "EstimatedRelativeError": the relative RMS error of the image estimated
 * from the samples themselves, by comparing the images of the first half of
 * the samples (for Hybrid, the coarser Halton run) and of the second half
 * (0 for an empty image, NaN for 1 or 2 samples, and NaN for an image of
 * every voxel, a cloud of vtkMCXTypes::EVERY_VOXEL or Strategy
 * EVERY_VOXEL here, which has no voxel-choice error to estimate, unless it
 * is empty; its "SampleCount" is the number of voxels).
 *
 * Deposit (index input; a footprint cloud from vtkMCXPointSampler brings its
 * own, and FootprintReach applies to it too): with FOOTPRINT each sample adds its voxel's
 * reconstruction kernel, integrated along the view and averaged over each
 * pixel's area, to every pixel the kernel reaches (Core/mcxFootprint.h);
 * no random kernel offset is left (only the sub-pixel phase is rounded at
 * random), and with a stratified voxel choice (HYBRID, QUASI_MONTE_CARLO)
 * the error falls about as M^-1 instead of M^-1/2. A kernel reaching more than FootprintReach
 * pixels along a projected voxel axis is split into a random coarse part and a deposited fine part,
 * which bounds a sample's cost and keeps the estimate unbiased. FOOTPRINT is the default; POINT is
 * the paper's estimator: one count where the sample's random offset lands. The estimand is the
 * same.
 *
 * Target-accuracy controls (index input): with TargetRelativeError or
 * TargetQuantizationLevels set, a pilot run (at least 2^16 - 1 samples, about
 * 4 per pixel) measures the image and the sample count is chosen to meet the
 * target -- the relative RMS error (scaled as M^-1/2), or the paper's
 * criterion (its equation 1) that the average pixel deviation stays below
 * one of L grey levels, M > (W H - 1) B^2 L^2 with B the mean over the
 * maximum of the image -- and checked again on the larger run (up to three
 * times), within 2^MaximumSampleExponent - 1 samples (a warning says so when
 * those fall short of the target). SampleExponent is then ignored, and
 * "SampleCount" tells the count used.
 *
 * Channels (index input): with SetNumberOfChannels(K) and a fraction
 * function per channel (SetChannelFraction), each sample drawn under the
 * TF is also split into K line-integral channels by its level's fractions
 * f_c(value) / sum over c of f_c(value): one sampling pass makes the total
 * image and the K channel images (e.g. each material's g/cm^3 x mm for a
 * polychromatic radiograph, vtkMCXPolychromaticRadiograph). The output
 * then carries "ChannelLineIntegral" (K components) and field data
 * "ChannelEstimatedRelativeError" (K values, estimated as the image's).
 * The split is exact: the channels' fixed-point sums add up to the total's,
 * bit for bit, for any number of threads and processes, every deposit and
 * strategy of an index input and the target controls (which aim at the
 * total's error). A point-cloud input is not split (an error).
 */
#ifndef vtkMCXProjector_h
#define vtkMCXProjector_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXPointSampler.h"          // for the sample-count limits
#include "vtkMCXProjectorBase.h"
#include "vtkPiecewiseFunction.h" // for the channel fractions
#include "vtkSmartPointer.h"      // for the channel fractions

#include <vector> // for the channel fractions

class vtkMultiProcessController;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXProjector : public vtkMCXProjectorBase
{
public:
  static vtkMCXProjector* New();
  vtkTypeMacro(vtkMCXProjector, vtkMCXProjectorBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * With an index input: M = 2^SampleExponent - 1 samples (default
   * vtkMCXTypes::DefaultSampleExponent, 22),
   * the sampling strategy (vtkMCXTypes::HYBRID, MONTE_CARLO,
   * QUASI_MONTE_CARLO, or EVERY_VOXEL: each voxel of non-zero weight once,
   * weighted by its TF weight over the mean, never stored; SampleExponent
   * is unused and the target controls must be 0, else an error) and the
   * seed. Ignored for a point-cloud input (a VIEW_ORDERED cloud too: that
   * strategy is the sampler's alone, since one projection would pay its
   * sort of every voxel; SetStrategy(VIEW_ORDERED) is an error that keeps
   * the strategy).
   */
  vtkSetClampMacro(SampleExponent, int, 0, vtkMCXTypes::LargestSampleExponent);
  vtkGetMacro(SampleExponent, int);
  void SetNumberOfSamples(vtkTypeInt64 n);
  vtkTypeInt64 GetNumberOfSamples();
  virtual void SetStrategy(int strategy);
  vtkGetMacro(Strategy, int);
  vtkSetClampMacro(Seed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(Seed, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * vtkMCXTypes::FOOTPRINT (default) or POINT, and the footprint's
   * reach in pixels per projected voxel axis (default 16, 0.5 to 32).
   */
  vtkSetClampMacro(Deposit, int, vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT);
  vtkGetMacro(Deposit, int);
  void SetDepositToPoint() { this->SetDeposit(vtkMCXTypes::POINT); }
  void SetDepositToFootprint() { this->SetDeposit(vtkMCXTypes::FOOTPRINT); }
  vtkSetClampMacro(FootprintReach, double, 0.5, 32.0);
  vtkGetMacro(FootprintReach, double);
  ///@}

  ///@{
  /** Relative RMS error to reach (0, the default: use SampleExponent). */
  vtkSetClampMacro(TargetRelativeError, double, 0.0, 1.0);
  vtkGetMacro(TargetRelativeError, double);
  ///@}

  ///@{
  /**
   * Under a target (TargetRelativeError or TargetQuantizationLevels) with an
   * index input, choose the deposit by measurement instead of Deposit: a
   * pilot run of each deposit measures its error and its seconds, and the
   * one predicted to reach the target soonest is refined; every voxel once
   * competes for relative-error targets (its error taken as the footprint
   * pilot's extrapolated to every voxel, its time as that many footprints).
   * The output's field data Deposit and Strategy say what was chosen. Off by
   * default: the choice rests on measured times, so near a tie a busy
   * machine may choose differently from one run to the next (each image
   * meets the target, but is not the same bit for bit).
   */
  vtkSetMacro(ChooseDepositForTarget, bool);
  vtkGetMacro(ChooseDepositForTarget, bool);
  vtkBooleanMacro(ChooseDepositForTarget, bool);
  ///@}

  ///@{
  /** Grey levels L of the paper's quantization criterion (0, the default: off). */
  vtkSetClampMacro(TargetQuantizationLevels, int, 0, 65536);
  vtkGetMacro(TargetQuantizationLevels, int);
  ///@}

  ///@{
  /**
   * The processes that share the work (default: the global controller).
   * Under more than one, an index input is requested as z-slabs, one per
   * process; each process deposits the samples whose voxels its slab holds
   * (with the numbering of a single process), and the exact sums are added
   * over the processes: the output of process 0 is, bit for bit, the image
   * one process makes of the whole volume, for any number of processes, and
   * the other processes' outputs are empty (as with VTK's other parallel
   * filters whose result is one dataset). A point-cloud input is projected
   * by each process alone.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /** Upper bound of the exponent the target controls may choose (default 30). */
  vtkSetClampMacro(MaximumSampleExponent, int, vtkMCXTypes::PilotSampleExponent,
    vtkMCXTypes::LargestSampleExponent);
  vtkGetMacro(MaximumSampleExponent, int);
  ///@}

  ///@{
  /**
   * The channels the deposit is split into (0, the default: none; at most
   * 64) and channel c's fraction function of the data value (>= 0; null:
   * no image can be made while channels are asked for). At every level the
   * TF weighs, the fractions must not all be 0. Setting fewer channels
   * drops the functions beyond them.
   */
  void SetNumberOfChannels(int channels);
  int GetNumberOfChannels() const;
  void SetChannelFraction(int c, vtkPiecewiseFunction* fraction);
  vtkPiecewiseFunction* GetChannelFraction(int c) const;
  ///@}

  /** Folds in the channel fraction functions' times. */
  vtkMTimeType GetMTime() override;

protected:
  vtkMCXProjector();
  ~vtkMCXProjector() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  std::string AgreeOnFailure(vtkInformation* inInfo, const std::string& failure) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SampleExponent = vtkMCXTypes::DefaultSampleExponent;
  int Strategy = vtkMCXTypes::HYBRID;
  vtkTypeInt64 Seed = 0;
  int Deposit = vtkMCXTypes::FOOTPRINT;
  double FootprintReach = 16.0;
  double TargetRelativeError = 0.0;
  int TargetQuantizationLevels = 0;
  bool ChooseDepositForTarget = false;
  int MaximumSampleExponent = 30;
  vtkMultiProcessController* Controller = nullptr;
  std::vector<vtkSmartPointer<vtkPiecewiseFunction>> ChannelFractions;

private:
  vtkMCXProjector(const vtkMCXProjector&) = delete;
  void operator=(const vtkMCXProjector&) = delete;
};

#endif
