/**
 * @class   vtkMCXTypes
 * @brief   The names and numbers every MonteCarloXRay class shares: sampling
 *          strategies, reconstruction kernels, deposits, the sample-count
 *          limits and default, and the names of the data arrays.
 *
 * One home for them: the sampler, the projectors, the mapper, the ParaView
 * XML (its enumerations and defaults, checked against these values by
 * Python.XMLDefaults) and the mcxray command (its option names, through
 * StrategyFromName and the like) all read them here. Only static members.
 */
#ifndef vtkMCXTypes_h
#define vtkMCXTypes_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkObject.h"

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXTypes : public vtkObject
{
public:
  static vtkMCXTypes* New();
  vtkTypeMacro(vtkMCXTypes, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How the sampler chooses voxels (vtkMCXPointSampler::SetStrategy). */
  enum StrategyType
  {
    HYBRID = 0,            ///< Halton voxel choice, pseudo-random offset (the paper)
    MONTE_CARLO = 1,       ///< pseudo-random voxel choice and offset
    QUASI_MONTE_CARLO = 2, ///< Halton voxel choice and Halton (bases 3, 5, 7) offset
    EVERY_VOXEL = 3,       ///< each voxel of non-zero weight once, weighted
    VIEW_ORDERED = 4       ///< Halton choice in one view's pixel order, weighted
  };

  /** The reconstruction kernel h of g(x) = sum TF(f_ijk) h(x - x_ijk). */
  enum KernelType
  {
    TENT = 0, ///< trilinear reconstruction
    BOX = 1   ///< nearest-neighbour reconstruction
  };

  /** How a projector spreads a sample over the image (vtkMCXProjector::SetDeposit). */
  enum DepositType
  {
    POINT = 0,    ///< one count where the kernel's random offset lands (the paper's)
    FOOTPRINT = 1 ///< the voxel's kernel footprint over every pixel it reaches (the default)
  };

  ///@{
  /**
   * The sample counts of every class, as exponents m of M = 2^m - 1:
   * - LargestSampleExponent: samples projected as they are generated (never
   *   stored); M then still fits a signed 64-bit count;
   * - MaximumPointCloudExponent: a stored cloud (the sampler, the mapper):
   *   2^30 points take 12 GiB as float triples, more than the machines this
   *   runs on hold twice (the cloud and the renderer's copy);
   * - PilotSampleExponent: the smallest pilot run of the projector's
   *   target-accuracy controls, enough for the error estimate to settle;
   * - DefaultSampleExponent: the default of every class, the command line,
   *   Python and ParaView: 2^22 - 1 samples keep the footprint deposit's
   *   relative RMS error below 1 % on the accuracy report's CTs at their
   *   image sizes (Documentation/accuracy/convergence.csv) in a fraction of
   *   a second, as a stored cloud of about 50 MB an interactive view holds.
   */
  static constexpr int LargestSampleExponent = 63;
  static constexpr int MaximumPointCloudExponent = 30;
  static constexpr int PilotSampleExponent = 16;
  static constexpr int DefaultSampleExponent = 22;
  ///@}

  ///@{
  /**
   * The names the mcxray command gives the enumerations ("hybrid", "mc",
   * "qmc", "every-voxel", "view-ordered"; "tent", "box"; "point",
   * "footprint"), and the value of a name (-1 for an unknown one).
   */
  static const char* StrategyCommandName(int strategy);
  static const char* KernelCommandName(int kernel);
  static const char* DepositCommandName(int deposit);
  static int StrategyFromName(const char* name);
  static int KernelFromName(const char* name);
  static int DepositFromName(const char* name);
  ///@}

  ///@{
  /** Field data of a point cloud (vtkMCXPointSampler's output). */
  static const char* SampleWeightName() { return "SampleWeight"; }
  static const char* IntegralName() { return "Integral"; }
  static const char* SampleExponentName() { return "SampleExponent"; }
  /// How projectors deposit the points (POINT or FOOTPRINT), the kernel, the
  /// seed of the footprint's random parts, and the world edge vectors of a
  /// voxel (9 values, row-major: column k is edge k), which the footprint needs.
  static const char* DepositName() { return "Deposit"; }
  static const char* KernelName() { return "Kernel"; }
  static const char* StrategyName() { return "Strategy"; }
  static const char* SeedName() { return "Seed"; }
  static const char* VoxelAxesName() { return "VoxelAxes"; }
  /// The support's world corners (24 values, as SUPPORT_CORNERS), with which
  /// perspective projectors tabulate footprints for any prefix alike.
  static const char* SupportCornersName() { return "SupportCorners"; }
  /// VIEW_ORDERED with ControlVariate: the control image of the ordering
  /// view (one line integral per pixel, rows from the bottom) and that view
  /// (mcx::GeometryToValues' 23 values); see vtkMCXPointSampler::SetControlVariate.
  static const char* ControlImageName() { return "ControlImage"; }
  static const char* ControlViewName() { return "ControlView"; }
  /// The control image's own variance summed over its pixels (1 value, line
  /// integrals squared; 0 where it projects every voxel), which the image's
  /// error estimate adds (vtkMCXPointSampler::SetControlVoxelsPerPoint).
  static const char* ControlVarianceName() { return "ControlVariance"; }
  /// The first point of the cloud the control image was made with (3
  /// values; a prefix of the cloud keeps it), so that a filter that moves
  /// the points and passes the field data on leaves the control unused.
  static const char* ControlPointsName() { return "ControlPoints"; }
  ///@}

  /**
   * An optional point-data array of a cloud's consumers (vtkMCXProjector,
   * vtkMCXXRayMapper): point i counts PointWeight[i] times (one float or
   * double component, each finite and in [0, 2^40]; 0 skips the point), and
   * the points deposited carry the cloud's Integral together: a point of
   * weight w carries Integral w / (the sum of the weights deposited), in the
   * mapper's prefixes too, and the SampleWeight field is not read. Without
   * it every point counts once.
   */
  static const char* PointWeightName() { return "PointWeight"; }

  ///@{
  /** Field data of a density index (vtkMCXDensityIndex's output). */
  static const char* LevelValuesName() { return "LevelValues"; }
  static const char* LevelOffsetsName() { return "LevelOffsets"; }
  static const char* SortedVoxelIdsName() { return "SortedVoxelIds"; }
  static const char* NonFiniteVoxelCountName() { return "NonFiniteVoxelCount"; }
  static const char* LevelBinWidthName() { return "LevelBinWidth"; }
  ///@}

  ///@{
  /** Arrays of a projector's image (vtkMCXProjectorBase) and of a radiograph (vtkMCXRadiograph). */
  static const char* LineIntegralName() { return "LineIntegral"; }
  /// A projector's output: field data of the image's 3x4 projection matrix
  /// (12 values, row-major; mcxProjectionMatrix.h's layout: world to the
  /// column and the row counted from the top).
  static const char* ProjectionMatrixName() { return "ProjectionMatrix"; }
  static const char* SampleCountName() { return "SampleCount"; }
  static const char* EstimatedRelativeErrorName() { return "EstimatedRelativeError"; }
  /// A projector's output split into channels (vtkMCXProjector::
  /// SetNumberOfChannels): their line integrals, one component each, and
  /// field data of their estimated relative errors, one value each.
  static const char* ChannelLineIntegralName() { return "ChannelLineIntegral"; }
  static const char* ChannelEstimatedRelativeErrorName() { return "ChannelEstimatedRelativeError"; }
  static const char* IntensityName() { return "Intensity"; }
  static const char* AttenuationName() { return "Attenuation"; }
  ///@}

protected:
  vtkMCXTypes() = default;
  ~vtkMCXTypes() override = default;

private:
  vtkMCXTypes(const vtkMCXTypes&) = delete;
  void operator=(const vtkMCXTypes&) = delete;
};

#endif
